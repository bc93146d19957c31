#pragma once

#include <cmath>

namespace harbour::core {

/// The fastest speed from which a constant deceleration `deceleration`, applied in steps of `dt_s` (velocity
/// first, then position), stops within `distance`: v = a dt (sqrt(x + 1/4) - 1/2), x = 2 d / (a dt^2),
/// written x / (sqrt(x + 1/4) + 1/2) so that a tiny distance gives 2 d / dt, not a cancellation to zero.
inline double discrete_braking_speed(double distance, double deceleration, double dt_s) {
  const double a_dt = deceleration * dt_s;
  const double x = 2.0 * distance / (a_dt * dt_s);
  return a_dt * x / (std::sqrt(x + 0.25) + 0.5);
}

}  // namespace harbour::core
