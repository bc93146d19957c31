#pragma once

#include <chrono>
#include <memory>

#include "harbour/io/MotionFiles.h"
#include "harbour/io/PlatformLink.h"
#include "harbour/motion/MotionSystem.h"
#include "harbour/station/RealTimeLoop.h"

namespace harbour::station {

/// The motion platform wired to the running machine: at the washout's rate it reads the cab's specific force
/// and angular velocity from the newest snapshot, runs washout, limits and Stewart inverse kinematics, and
/// the driver sends the pose to the platform over UDP (engaged by the station, parked when it stops).
class MotionLink {
 public:
  MotionLink(const io::PlatformFile& platform, const motion::WashoutSettings& washout,
             const io::DriverSettings& driver);

  void engage() { driver_.engage(); }
  /// Parks the platform and keeps sending until it is down (the sequencer's park time).
  void park_and_wait();
  /// Called often by the station: one platform frame when its period has come.
  void update(RealTimeLoop& loop);
  motion::PlatformState state() const { return driver_.state(); }
  long frames() const { return frames_; }
  const motion::PlatformFrame& last_frame() const { return last_; }

 private:
  using Clock = std::chrono::steady_clock;
  double now_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  motion::MotionSystem motion_;
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
