#include "harbour/station/RemoteChannels.h"

#include <algorithm>
#include <cstdio>

#include "harbour/net/SceneMessages.h"

namespace harbour::station {

using Clock = std::chrono::steady_clock;

RemoteChannels::RemoteChannels(std::unique_ptr<net::ChannelServerLink> link,
                               std::vector<std::string> displays, std::int64_t attempt, Source source,
                               BulkSource bulk, Settings settings)
    : link_(std::move(link)),
      attempt_(attempt),
      source_(std::move(source)),
      bulk_(std::move(bulk)),
      settings_(settings) {
  for (std::string& display : displays)
    channels_.push_back(Channel{std::move(display)});
  thread_ = std::thread([this] { run(); });
}

RemoteChannels::~RemoteChannels() {
  stop();
}

void RemoteChannels::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
}

void RemoteChannels::say(std::string words) {
  const std::lock_guard lock(said_mutex_);
  said_.push_back(std::move(words));
}

std::vector<std::string> RemoteChannels::take_said() {
  const std::lock_guard lock(said_mutex_);
  std::vector<std::string> said;
  said.swap(said_);
  return said;
}

void RemoteChannels::hear(Clock::time_point now) {
  for (const net::ChannelReady& ready : link_->take_readies()) {
    if (ready.attempt() != attempt_) continue;  // a frame of the attempt before
    const std::string display = ready.display().to_string();
    const auto channel = std::find_if(channels_.begin(), channels_.end(),
                                      [&](const Channel& c) { return c.display == display; });
    if (channel == channels_.end()) {
      if (std::find(strangers_.begin(), strangers_.end(), display) == strangers_.end()) {
        strangers_.push_back(display);
        say("a channel draws display '" + display + "', not a remote display of this station's profile");
      }
      continue;
    }
    if (ready.leaving()) {  // stopped in order: not waited for, not lost
      if (channel->live) say("channel " + display + " (" + channel->host + ") left: the others go on");
      channel->live = false;
      continue;
    }
    channel->heard = now;
    channel->host = ready.host().to_string();
    channel->ready_frame = std::max<std::uint64_t>(channel->ready_frame, ready.frame());
    ++channel->frames_drawn;
    if (!channel->live) {
      channel->live = true;
      say("channel " + display + " (" + channel->host + ") draws frames");
    }
  }
}

void RemoteChannels::run() {
  std::uint64_t frame = 0;
  Clock::time_point sent_at{};
  bool sent_to_channels = false;  // the last frame went to a channel drawing
  std::vector<std::vector<std::uint32_t>> tiles_sent;
  Clock::time_point tiles_at{};
  const auto period = std::chrono::duration<double>(1.0 / settings_.max_fps);
  while (running_.load()) {
    const Clock::time_point now = Clock::now();
    hear(now);
    bool any_live = false, all_ready = true;
    for (Channel& c : channels_) {
      if (!c.live) continue;
      if (c.ready_frame < frame &&
          std::chrono::duration<double>(now - std::max(c.heard, sent_at)).count() > settings_.lost_after_s) {
        c.live = false;  // the others go on without it
        say("channel " + c.display + " lost: nothing drawn for " +
            std::to_string(static_cast<int>(settings_.lost_after_s * 1000)) + " ms; the others go on");
        continue;
      }
      any_live = true;
      all_ready = all_ready && c.ready_frame >= frame;
    }
    const double since_sent = std::chrono::duration<double>(now - sent_at).count();
    const bool due = frame == 0 || (any_live ? all_ready && since_sent >= period.count()
                                             : since_sent >= settings_.idle_period_s);
    const scene::Snapshot* snapshot = due ? source_() : nullptr;
    if (snapshot) {
      if (any_live && sent_to_channels) longest_frame_s_ = std::max(longest_frame_s_, since_sent);
      sent_to_channels = any_live;
      const scene::BulkView* bulk = bulk_ ? bulk_() : nullptr;
      if (bulk && std::chrono::duration<double>(now - tiles_at).count() >= settings_.tiles_every_s) {
        net::changed_bulk_tiles(*bulk, attempt_, tiles_sent,
                                [this](const net::ChannelBulkTile& tile) { link_->publish(tile); });
        tiles_at = now;
      }
      net::ChannelFrame message = net::channel_frame(*snapshot, bulk, attempt_);
      message.show_frame(frame);
      message.frame(++frame);
      link_->publish(std::move(message));
      sent_at = now;
      frames_ = static_cast<long>(frame);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
}

std::string RemoteChannels::summary() const {
  const double s = std::chrono::duration<double>(Clock::now() - start_).count();
  char line[160];
  std::snprintf(line, sizeof line,
                "remote channels: %ld frames in %.1f s (%.1f a second), longest between frames %.0f ms;",
                frames_.load(), s, s > 0 ? static_cast<double>(frames_.load()) / s : 0.0,
                longest_frame_s_ * 1000.0);
  std::string text = line;
  for (const Channel& c : channels_)
    text += " " + c.display +
            (c.frames_drawn > 0 ? " drew " + std::to_string(c.frames_drawn) : std::string(" never drew"));
  return text;
}

}  // namespace harbour::station
