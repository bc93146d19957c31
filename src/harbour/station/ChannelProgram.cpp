#include "harbour/station/ChannelProgram.h"

#include <unistd.h>

#include <osg/Image>
#include <osgDB/WriteFile>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "harbour/core/Text.h"
#include "harbour/ig/Visuals.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/net/DdsLink.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/records/Centre.h"
#include "harbour/station/DisplayDrawing.h"
#include "harbour/station/DisplayLayout.h"
#include "harbour/station/Profile.h"
#include "harbour/station/StationWindow.h"

namespace harbour::station {
namespace {

using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_channel_stop_signal(int) {
  g_stop = 1;
}

// A frame not shown within this long of being drawn is shown anyway (the station gone or stopped)
constexpr auto kLongestSwapWait = std::chrono::seconds(1);

std::int64_t monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

// The display this channel draws, as a profile of its own (its one display, full screen on this host's
// first output)
Profile channel_profile(const Profile& profile, const std::string& display, const std::string& size) {
  std::string remote;
  for (const DisplayChannel& d : profile.displays)
    if (d.remote) remote += (remote.empty() ? "" : ", ") + d.name;
  const auto found = std::find_if(profile.displays.begin(), profile.displays.end(),
                                  [&](const DisplayChannel& d) { return d.name == display; });
  if (found == profile.displays.end())
    throw std::runtime_error("profile " + profile.name + " has no display '" + core::printable(display) +
                             "' (remote ones: " + (remote.empty() ? "none" : remote) + ")");
  if (!found->remote)
    throw std::runtime_error(
        "display '" + display + "' of profile " + profile.name +
        " is drawn by the station itself (remote ones: " + (remote.empty() ? "none" : remote) + ")");
  Profile mine = with_displays(profile, [&](const DisplayChannel& d) { return d.name == display; });
  mine.windows = Profile::Windows::kPerDisplay;
  if (!size.empty()) {
    int width = 0, height = 0;
    char tail = 0;
    if (std::sscanf(size.c_str(), "%dx%d%c", &width, &height, &tail) != 2 || width < 64 || height < 64 ||
        width > 8192 || height > 8192)
      throw std::runtime_error("--size " + core::printable(size) + ": WIDTHxHEIGHT, 64 to 8192 each");
    mine.displays.front().width = width;
    mine.displays.front().height = height;
  }
  return mine;
}

// One attempt's frames drawn and shown in step with the station's other channels. Its source and its wait
// run on the render thread.
class FrameLock {
 public:
  FrameLock(net::ChannelFeed& feed, std::int64_t attempt, std::ofstream* log)
      : feed_(feed), attempt_(attempt), log_(log) {}

  // The next frame to draw (nullptr while none has come)
  const scene::Snapshot* next() {
    for (const net::ChannelBulkTile& tile : feed_.take_tiles())
      if (tile.attempt() == attempt_) net::apply_bulk_tile(tile, bulk_);
    if (!fresh_) take(std::chrono::milliseconds(20));
    if (!fresh_ || pending_.attempt() != attempt_) return nullptr;
    fresh_ = false;
    net::read_channel_frame(pending_, snapshot_, &bulk_);
    snapshot_.step = static_cast<std::int64_t>(pending_.frame());  // each frame drawn, held or not
    drawing_ = pending_.frame();
    step_ = pending_.step();
    time_s_ = pending_.time_s();
    draw_started_ = Clock::now();
    return &snapshot_;
  }
  const scene::BulkView* bulk() const { return bulk_.grids.empty() ? nullptr : &bulk_; }

  // Drawn: says so, and waits for the station's word to show it (the next frame)
  void wait_to_show() {
    const auto drawn = Clock::now();
    const std::int64_t drawn_ns = monotonic_ns();
    net::ChannelReady ready;
    ready.host(core::host_name().substr(0, 64));
    ready.attempt(attempt_);
    ready.frame(drawing_);
    ready.shown_frame(shown_);
    ready.shown_ns(shown_ns_);
    ready.draw_ms(
        static_cast<float>(std::chrono::duration<double, std::milli>(drawn - draw_started_).count()));
    feed_.ready(ready);
    while (!(fresh_ && pending_.frame() > drawing_) && Clock::now() - drawn < kLongestSwapWait && !g_stop)
      take(kLongestSwapWait - (Clock::now() - drawn));
    shown_ = drawing_;
    shown_ns_ = monotonic_ns();
    ++frames_shown_;
    if (log_)
      *log_ << shown_ << ',' << step_ << ',' << time_s_ << ',' << drawn_ns << ',' << shown_ns_ << ','
            << ready.draw_ms() << '\n';
  }
  long frames_shown() const { return frames_shown_; }

 private:
  void take(Clock::duration wait) {
    if (feed_.take_frame(pending_)) {
      fresh_ = true;
      return;
    }
    if (feed_.wait_for_frame(std::chrono::duration_cast<std::chrono::nanoseconds>(wait)) &&
        feed_.take_frame(pending_))
      fresh_ = true;
  }

  net::ChannelFeed& feed_;
  std::int64_t attempt_;
  std::ofstream* log_;
  net::ChannelFrame pending_;
  bool fresh_ = false;  // pending_ not yet drawn
  scene::Snapshot snapshot_;
  scene::BulkView bulk_;
  std::uint64_t drawing_ = 0, shown_ = 0;
  std::int64_t shown_ns_ = 0, step_ = 0;
  double time_s_ = 0.0;
  Clock::time_point draw_started_;
  long frames_shown_ = 0;
};

// The last picture shown, kept for --picture
class LastPicture {
 public:
  void keep(const osg::Image& image) {
    const std::lock_guard lock(mutex_);
    image_ = new osg::Image(image, osg::CopyOp::DEEP_COPY_ALL);
  }
  bool write(const std::string& path) {
    const std::lock_guard lock(mutex_);
    return image_ && osgDB::writeImageFile(*image_, path);
  }

 private:
  std::mutex mutex_;
  osg::ref_ptr<osg::Image> image_;
};

// One attempt drawn: the scene as the station sent it, its frames as they come
struct AttemptDrawing {
  std::int64_t attempt = 0;
  scene::SceneDescription scene;
  std::unique_ptr<FrameLock> lock;
  std::unique_ptr<ig::RenderThread> render;
};

void draw_attempt(AttemptDrawing& drawing, const net::StationScene& message, net::ChannelFeed& feed,
                  const Profile& profile, const DisplayLayout& layout, StationWindow* window,
                  LastPicture* last, std::ofstream* log) {
  if (drawing.render) drawing.render->stop();
  drawing.render.reset();
  drawing.attempt = message.attempt();
  drawing.scene = net::scene_from(message);
  drawing.lock = std::make_unique<FrameLock>(feed, drawing.attempt, log);
  FrameLock* lock = drawing.lock.get();
  drawing.render = draw_displays(
      profile, layout, drawing.scene,
      ig::load_shipped_looks(records::shipped_data_folder(), sim::machine_kinds()),
      [lock] { return lock->next(); }, [lock] { return lock->bulk(); },
      [window, last](int, const osg::Image& image, int x0, std::uint8_t colours, bool is_last) {
        if (window)
          window->hand_over(image.data(), image.s(), image.t(),
                            static_cast<int>(image.getPixelSizeInBits() / 8), image.getRowStepInBytes(), x0,
                            colours, is_last);
        if (is_last && last) last->keep(image);
      },
      [lock](const scene::Snapshot&) { lock->wait_to_show(); }, 0.0, ig::RenderThread::Priority::kNormal);
  std::printf("drawing attempt %lld of station %s: %s, %zu entities\n",
              static_cast<long long>(drawing.attempt), message.station().c_str(),
              drawing.scene.machine.c_str(), drawing.scene.entities.size());
  std::fflush(stdout);
}

// A scene sent again within the attempt: the entities renamed since (a box handed over)
void rename_changed(AttemptDrawing& drawing, const net::StationScene& message) {
  const scene::SceneDescription now = net::scene_from(message);
  for (std::size_t n = 0; n < now.entities.size() && n < drawing.scene.entities.size(); ++n)
    if (now.entities[n].name != drawing.scene.entities[n].name) {
      drawing.render->rename_entity(n, now.entities[n].name);
      drawing.scene.entities[n].name = now.entities[n].name;
    }
}

}  // namespace

int run_channel(const ChannelOptions& options) {
  g_stop = 0;
  std::signal(SIGINT, on_channel_stop_signal);
  std::signal(SIGTERM, on_channel_stop_signal);
  if (const std::string why = net::why_bad_node_name(options.station); !why.empty())
    throw std::runtime_error("--station '" + core::printable(options.station) + "': " + why);
  if (options.window != "on" && options.window != "off" && options.window != "auto")
    throw std::runtime_error("--window " + core::printable(options.window) + ": on, off or auto");
  const Profile full = load_profile(resolve_profile(options.profile, records::shipped_data_folder()));
  const Profile profile = channel_profile(full, options.display, options.size);
  const DisplayChannel& display = profile.displays.front();
  const DisplayLayout layout = layout_displays(profile, display.width);
  std::unique_ptr<StationWindow> window;
  const bool screen = std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY");
  if (options.window == "on" || (options.window == "auto" && screen))
    window = std::make_unique<StationWindow>(layout.windows[0].width, layout.windows[0].height,
                                             "harboursim: " + options.station + ", " + display.name,
                                             display.fullscreen, 0);
  std::optional<std::ofstream> log;
  if (!options.log.empty()) {
    log.emplace(options.log);
    if (!*log) throw std::runtime_error(options.log + ": cannot be written");
    *log << "frame,step,time_s,drawn_ns,shown_ns,draw_ms\n";
  }
  net::ChannelFeed feed(options.station, display.name, options.domain);
  std::printf("channel %s of station %s (%s, %dx%d%s): waiting for its frames on DDS domain %d\n",
              display.name.c_str(), options.station.c_str(), full.name.c_str(), layout.render_width,
              layout.render_height, window ? ", in a window" : ", no window", options.domain);
  std::fflush(stdout);
  LastPicture last;
  AttemptDrawing drawing;
  const auto start = Clock::now();
  bool open = true;
  while (!g_stop && open) {
    if (const std::optional<net::StationScene> scene = feed.take_scene()) {
      if (!drawing.render || scene->attempt() != drawing.attempt)
        draw_attempt(drawing, *scene, feed, profile, layout, window.get(),
                     options.picture.empty() ? nullptr : &last, log ? &*log : nullptr);
      else
        rename_changed(drawing, *scene);
    }
    if (window) open = window->pump().open;
    if (drawing.render && !drawing.render->error().empty())
      throw std::runtime_error("image generator: " + drawing.render->error());
    if (options.seconds > 0.0 && Clock::now() - start >= std::chrono::duration<double>(options.seconds))
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (drawing.render) {
    drawing.render->stop();
    feed.leave(drawing.attempt);  // (after its last ready) the station goes on without this channel at once
    std::printf("channel %s: %ld frames shown (%.1f a second)\n", display.name.c_str(),
                drawing.lock->frames_shown(), drawing.render->fps());
  }
  if (!options.picture.empty() && !last.write(options.picture))
    throw std::runtime_error(options.picture + ": no picture shown, or it cannot be written");
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  return 0;
}

}  // namespace harbour::station
