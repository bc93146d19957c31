#include "harbour/machines/parts/Drive.h"

#include <algorithm>
#include <cmath>

#include "harbour/core/Braking.h"

namespace harbour::sim {

DriveOutput Drive::step(double lever, double position_m, double dt_s, bool emergency_stop, bool brake_fault) {
  const DriveSettings& s = settings_;
  double target = emergency_stop ? 0.0 : std::clamp(lever, -1.0, 1.0) * s.max_speed_mps;

  // slow down ahead of the limit switches: no faster than what stops on them at the service deceleration
  const double room_up = std::max(0.0, s.max_position_m - position_m);
  const double room_down = std::max(0.0, position_m - s.min_position_m);
  target = std::min(target, core::discrete_braking_speed(room_up, s.deceleration_mps2, dt_s));
  target = std::max(target, -core::discrete_braking_speed(room_down, s.deceleration_mps2, dt_s));

  // a limit reached while the operator pushes into it counts once
  const bool pushing_into_limit = (lever > 0.0 && room_up <= 0.0) || (lever < 0.0 && room_down <= 0.0);
  if (pushing_into_limit && !at_limit_) ++limit_hits_;
  at_limit_ = pushing_into_limit;

  // ramp the reference: accelerate at the acceleration limit, slow at the deceleration (or emergency) limit
  const bool slowing = std::abs(target) < std::abs(reference_) || target * reference_ < 0.0;
  const double rate =
      emergency_stop ? s.emergency_deceleration_mps2 : (slowing ? s.deceleration_mps2 : s.acceleration_mps2);
  reference_ += std::clamp(target - reference_, -rate * dt_s, rate * dt_s);

  DriveOutput out;
  if (reference_ == 0.0 && target == 0.0 && !brake_fault) {
    out.brake = true;
    out.max_force_n = s.brake_force_n;
  } else {
    out.velocity_mps = reference_;
    out.max_force_n = s.max_force_n;
  }
  return out;
}

DriveOutput HydraulicDrive::step(double lever, double position_m, double dt_s, bool emergency_stop) {
  DriveOutput out = drive_.step(lever, position_m, dt_s, emergency_stop);
  if (!tracking_) target_m_ = position_m, tracking_ = true;
  target_m_ += out.velocity_mps * dt_s;
  target_m_ = std::clamp(target_m_, position_m - kSlack_m, position_m + kSlack_m);
  out.velocity_mps += (target_m_ - position_m) / kFollow_s;
  return out;
}

}  // namespace harbour::sim
