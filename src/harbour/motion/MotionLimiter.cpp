#include "harbour/motion/MotionLimiter.h"

#include "harbour/core/Braking.h"

#include <algorithm>
#include <cmath>

namespace harbour::motion {
const PlatformPose& MotionLimiter::step(const PlatformPose& target, double dt_s) {
  // the velocity that lands on the target this step, scaled as one vector into the speed limits and each
  // axis's braking curve (so no axis overshoots its target)
  const PlatformPose error = target - pose_;
  PlatformPose wanted = error * (1.0 / dt_s);
  double speed_scale = 1.0;
  for (int i = 0; i < kDofCount; ++i) {
    const double cap =
        std::min(limits_.max_velocity[i],
                 core::discrete_braking_speed(std::abs(error[i]), limits_.max_acceleration[i], dt_s));
    if (std::abs(wanted[i]) > cap) speed_scale = std::min(speed_scale, cap / std::abs(wanted[i]));
  }
  wanted = wanted * speed_scale;

  // one step toward that velocity, the change scaled as one vector into the acceleration limits
  const PlatformPose change = wanted - velocity_;
  double scale = 1.0;
  for (int i = 0; i < kDofCount; ++i)
    if (std::abs(change[i]) > limits_.max_acceleration[i] * dt_s)
      scale = std::min(scale, limits_.max_acceleration[i] * dt_s / std::abs(change[i]));
  velocity_ = velocity_ + change * scale;
  pose_ = pose_ + velocity_ * dt_s;
  return pose_;
}

}  // namespace harbour::motion
