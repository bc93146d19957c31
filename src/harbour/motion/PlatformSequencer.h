#pragma once

#include <cstdint>

#include "harbour/motion/MotionLimiter.h"
#include "harbour/motion/PlatformPose.h"

namespace harbour::motion {

/// Life cycle of a platform as the driver sees it.
enum class PlatformState : std::uint8_t { kParked, kEngaging, kEngaged, kFading, kParking };

/// Engage/park and watchdog timing (settings).
struct SequencerSettings {
  double engage_time_s = 5.0;        ///< [s] parked to neutral
  double park_time_s = 5.0;          ///< [s] current pose to parked
  double watchdog_timeout_s = 0.25;  ///< [s] without a fresh pose before fading to neutral
  MotionLimits fade_limits;          ///< slow limits used while fading to neutral
  PlatformPose parked_pose;          ///< pose at rest on the end stops (heave below neutral)
};

/// The platform-side state machine: engages and parks on smooth profiles, passes commanded poses while
/// engaged, and when commands stop arriving brings the platform slowly to neutral (the watchdog).
class PlatformSequencer {
 public:
  explicit PlatformSequencer(const SequencerSettings& settings);

  void engage();
  void park();
  /// Advances by `dt_s`; `command` is the latest pose received and `command_age_s` how old it is.
  const PlatformPose& step(double dt_s, const PlatformPose& command, double command_age_s);

  PlatformState state() const { return state_; }
  const PlatformPose& pose() const { return pose_; }

 private:
  SequencerSettings settings_;
  PlatformState state_ = PlatformState::kParked;
  PlatformPose pose_;
  PlatformPose profile_start_;
  double progress_ = 0.0;  // [-] 0..1 along an engage or park profile
  MotionLimiter fader_;
};

}  // namespace harbour::motion
