#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "harbour/net/DdsLink.h"
#include "harbour/scene/BulkView.h"
#include "harbour/scene/Snapshot.h"

namespace harbour::station {

/// A station's remote image-generator channels (`harboursim channel`, a projector's host each): a thread that
/// sends them the newest snapshot as frames, frame-locked as a swap group (frame N + 1, carrying "show N",
/// goes once every channel it hears has drawn N; one silent for `lost_after_s` is left out until it speaks
/// again), and the bulk material's tiles as they change.
class RemoteChannels {
 public:
  using Source = std::function<const scene::Snapshot*()>;
  using BulkSource = std::function<const scene::BulkView*()>;
  struct Settings {
    double max_fps = 60.0;       ///< a projector's refresh
    double lost_after_s = 0.5;   ///< a channel silent this long while the others wait is left out
    double idle_period_s = 0.5;  ///< frames while no channel draws (one that starts has one at once)
    double tiles_every_s = 0.1;  ///< the bulk material's changed tiles
  };
  /// The channels drawing `displays` (the profile's remote displays' names) of attempt `attempt`.
  RemoteChannels(std::unique_ptr<net::ChannelServerLink> link, std::vector<std::string> displays,
                 std::int64_t attempt, Source source, BulkSource bulk, Settings settings);
  ~RemoteChannels();
  RemoteChannels(const RemoteChannels&) = delete;
  RemoteChannels& operator=(const RemoteChannels&) = delete;
  void stop();

  /// What the channels did since the last call, in words ("channel left (host-2) draws frames", "... lost").
  std::vector<std::string> take_said();
  /// Frames sent, the rate, and the channels locked, in words.
  std::string summary() const;
  long frames() const { return frames_.load(); }

 private:
  struct Channel {
    std::string display, host;
    bool live = false;
    std::chrono::steady_clock::time_point heard;
    std::uint64_t ready_frame = 0;
    long frames_drawn = 0;
  };
  void run();
  void hear(std::chrono::steady_clock::time_point now);
  void say(std::string words);

  std::unique_ptr<net::ChannelServerLink> link_;
  std::vector<Channel> channels_;
  std::int64_t attempt_;
  Source source_;
  BulkSource bulk_;
  Settings settings_;
  std::thread thread_;
  std::atomic<bool> running_{true};
  std::atomic<long> frames_{0};
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  // between two frames while channels drew (the run thread's; read after stop)
  double longest_frame_s_ = 0.0;
  mutable std::mutex said_mutex_;
  std::vector<std::string> said_;
  std::vector<std::string> strangers_;  // displays heard that are not this profile's remote ones
};

}  // namespace harbour::station
