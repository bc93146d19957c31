#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "harbour/audio/AudioOut.h"

namespace harbour::audio {

/// The station's sound on its own thread: a few 10 ms blocks ahead of the output device, each rendered from
/// the newest snapshot the loop has published for it. Mute and volume may change from any thread.
class SoundThread {
 public:
  /// Opens the device (AudioError where there is none) and starts; `latest` gives the newest snapshot or
  /// nullptr before the first. The exercise's radio calls are spoken first (a language espeak-ng lacks:
  /// no radio, and radio_problem() says why).
  SoundThread(const scene::SceneDescription& scene, const SoundSettings& sounds,
              const AudioSettings& settings, const scene::RadioScript& radio,
              std::function<const scene::Snapshot*()> latest);
  ~SoundThread();
  SoundThread(const SoundThread&) = delete;
  SoundThread& operator=(const SoundThread&) = delete;

  /// The output as the station's log names it.
  std::string describe() const { return described_; }
  /// The instructor's mute and volume ([0, 2], the profile's at the start).
  void set_volume(double volume) { volume_.store(volume); }
  void set_muted(bool muted) { muted_.store(muted); }
  double volume() const { return volume_.load(); }
  bool muted() const { return muted_.load(); }
  /// Blocks rendered so far.
  long blocks() const { return blocks_.load(); }
  /// A radio call heard as soon as it is spoken (the instructor's; spoken on the calling thread); throws
  /// AudioError when it cannot be spoken or there is no radio.
  void say(const std::string& text);
  const std::string& radio_problem() const { return radio_problem_; }

 private:
  static constexpr int kBlocksAhead =
      4;  // 40 ms: enough to ride out a busy moment, short enough to feel live
  void run();

  SoundScape scape_;
  std::unique_ptr<AudioOut> out_;
  std::function<const scene::Snapshot*()> latest_;
  std::string described_, radio_problem_;
  std::mutex said_mutex_;
  std::vector<std::shared_ptr<const std::vector<float>>> said_;
  std::atomic<double> volume_;
  std::atomic<bool> muted_{false}, stop_{false};
  std::atomic<long> blocks_{0};
  std::thread thread_;
};

}  // namespace harbour::audio
