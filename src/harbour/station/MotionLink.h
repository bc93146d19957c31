#pragma once

#include <chrono>
#include <memory>
#include <mutex>

#include "harbour/io/MotionFiles.h"
#include "harbour/io/PlatformLink.h"
#include "harbour/motion/MotionSystem.h"
#include "harbour/station/RealTimeLoop.h"

namespace harbour::station {

/// The platform's short cues from the same published figures the cab's sound is made of: the engine's speed
/// and load (the machine's drive named "engine"; a machine without one gives no engine cue) and the closing
/// speed of the impacts since the last frame.
class ShortCueSource {
 public:
  explicit ShortCueSource(const scene::SceneDescription& scene);
  motion::ShortCueInputs next(const scene::Snapshot& snapshot);

 private:
  int engine_ = -1;
  std::int64_t knocks_seen_ = -1;
};

/// The motion platform wired to the running machine: at the washout's rate it reads the cab's specific force
/// and angular velocity from the newest snapshot, runs washout, limits and Stewart inverse kinematics, and
/// the driver sends the pose to the platform over UDP (engaged by the station, parked when it stops).
class MotionLink {
 public:
  MotionLink(const io::PlatformFile& platform, const motion::WashoutSettings& washout,
             const io::DriverSettings& driver, const scene::SceneDescription& scene);

  void engage() {
    const std::lock_guard lock(mutex_);
    driver_.engage();
  }
  /// Parks the platform and keeps sending until it is down (the sequencer's park time).
  void park_and_wait();
  /// Called often by the station: one platform frame when its period has come.
  void update(RealTimeLoop& loop);
  /// What it is doing (any thread).
  motion::PlatformState state() const {
    const std::lock_guard lock(mutex_);
    return driver_.state();
  }
  long frames() const {
    const std::lock_guard lock(mutex_);
    return frames_;
  }
  motion::PlatformFrame last_frame() const {
    const std::lock_guard lock(mutex_);
    return last_;
  }

 private:
  using Clock = std::chrono::steady_clock;
  double now_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  mutable std::mutex mutex_;  // the station's monitor updates; the console and tests look
  motion::MotionSystem motion_;
  ShortCueSource short_cues_;
  io::PlatformDriver driver_;
  double period_s_;
  double park_time_s_;
  Clock::time_point start_ = Clock::now();
  double next_s_ = 0.0;
  std::int64_t last_step_ = -1;
  long frames_ = 0;
  motion::PlatformFrame last_;
};

}  // namespace harbour::station
