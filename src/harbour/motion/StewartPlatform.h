#pragma once

#include <array>

#include "harbour/core/Vec3.h"
#include "harbour/motion/PlatformPose.h"

namespace harbour::motion {

/// Number of actuators of a Stewart platform.
inline constexpr int kActuators = 6;
using ActuatorLengths = std::array<double, kActuators>;

/// Geometry of a 6-6 Stewart platform (settings). Actuator i joins base_joints[i] to platform_joints[i].
struct StewartGeometry {
  std::array<core::Vec3, kActuators> base_joints;  ///< [m] in the base frame (z up, origin on the floor)
  std::array<core::Vec3, kActuators>
      platform_joints;            ///< [m] in the platform frame (origin: the pose's point)
  double neutral_height_m = 1.0;  ///< [m] platform origin above the base origin at neutral
  double min_length_m = 0.0;      ///< [m] shortest actuator (joint to joint)
  double max_length_m = 0.0;      ///< [m] longest actuator
};

/// Inverse and forward kinematics of a Stewart platform.
class StewartPlatform {
 public:
  explicit StewartPlatform(const StewartGeometry& geometry) : geometry_(geometry) {}

  /// Actuator lengths [m] for a pose relative to neutral.
  ActuatorLengths inverse(const PlatformPose& pose) const;
  /// Newton iteration from `io_pose` (initial guess, e.g. the last pose) to the pose giving `lengths`;
  /// returns false if it did not converge to `tolerance_m` within `max_iterations`.
  bool forward(const ActuatorLengths& lengths, PlatformPose& io_pose, int max_iterations = 30,
               double tolerance_m = 1e-12) const;
  /// True when every length lies within the actuator stroke shortened by `margin_m` at both ends.
  bool reachable(const ActuatorLengths& lengths, double margin_m = 0.0) const;
  /// The largest s in [0, 1] with s * pose reachable within the margin (bisection to 1e-6): scales the whole
  /// cue.
  double largest_reachable_scale(const PlatformPose& pose, double margin_m = 0.0) const;

  const StewartGeometry& geometry() const { return geometry_; }

 private:
  StewartGeometry geometry_;
};

}  // namespace harbour::motion
