#pragma once

#include "harbour/motion/PlatformPose.h"

namespace harbour::motion {

/// Per-axis velocity and acceleration limits of the platform: [m/s], [rad/s]; [m/s^2], [rad/s^2].
struct MotionLimits {
  PlatformPose max_velocity;
  PlatformPose max_acceleration;
};

/// Follows a target pose within per-axis velocity and acceleration limits. Every correction scales the
/// whole change vector (all six axes together), so the cue keeps its direction; the velocity is also capped
/// so each axis can still brake to its target at its acceleration limit.
class MotionLimiter {
 public:
  explicit MotionLimiter(const MotionLimits& limits) : limits_(limits) {}

  /// Advances by `dt_s` toward `target`; returns the new pose.
  const PlatformPose& step(const PlatformPose& target, double dt_s);
  const PlatformPose& pose() const { return pose_; }
  const PlatformPose& velocity() const { return velocity_; }
  void reset(const PlatformPose& pose) {
    pose_ = pose;
    velocity_ = {};
  }

 private:
  MotionLimits limits_;
  PlatformPose pose_;
  PlatformPose velocity_;
};

}  // namespace harbour::motion
