#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "harbour/ig/ImageGenerator.h"

namespace harbour::ig {

/// The image generator on a thread of its own (its OpenGL context lives there): it draws the newest snapshot
/// the source hands it, at most `max_fps` frames a second (a display's refresh; 0: as fast as it can), in the
/// lowest scheduling class (SCHED_IDLE, which the renderer's worker threads inherit), so drawing never holds
/// the 1 kHz step back (unless asked to run as any thread).
class RenderThread {
 public:
  /// The newest snapshot (nullptr while there is none); called on the render thread only.
  using Source = std::function<const scene::Snapshot*()>;
  /// Called with each display channel's picture of a frame on the render thread (a window, a file, a video).
  using FrameSink = std::function<void(ImageGenerator&, const scene::Snapshot&, int channel)>;

  /// The newest view of the bulk material (nullptr where there is none); called on the render thread only.
  using BulkSource = std::function<const scene::BulkView*()>;

  /// How it is scheduled: below the simulation on the station's host, or as any thread (a host that only
  /// draws)
  enum class Priority { kBelowSimulation, kNormal };

  RenderThread(scene::SceneDescription scene, Looks looks, int width, int height, std::vector<View> views,
               Source source, FrameSink sink = {}, double max_fps = 60.0, BulkSource bulk = {},
               Priority priority = Priority::kBelowSimulation);
  ~RenderThread();
  void stop();
  long frames() const { return frames_.load(); }
  /// Frames per second since the start.
  double fps() const;
  /// Why the thread stopped early ("" while it runs or after stop()).
  std::string error() const;
  /// Text over the picture from the next frame on (ImageGenerator::set_overlay); any thread.
  void set_overlay(std::string text);
  /// Entity `index` is `name` from the next frame on (ImageGenerator::rename_entity); any thread.
  void rename_entity(std::size_t index, std::string name);

 private:
  void run(scene::SceneDescription scene, Looks looks, int width, int height, std::vector<View> views);

  Source source_;
  FrameSink sink_;
  BulkSource bulk_;
  double max_fps_;
  Priority priority_;
  std::thread thread_;
  std::atomic<bool> running_{true};
  std::atomic<long> frames_{0};
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  mutable std::mutex error_mutex_;
  std::string error_;
  std::mutex requests_mutex_;  // what other threads ask of the next frame
  std::string overlay_;
  std::vector<std::pair<std::size_t, std::string>> renames_;
  bool overlay_changed_ = false;
};

}  // namespace harbour::ig
