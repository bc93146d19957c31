#pragma once

#include <numbers>

namespace harbour::core {

/// Standard gravity [m/s^2] (CGPM 1901).
inline constexpr double kStandardGravity = 9.80665;

/// Degrees to radians.
constexpr double deg_to_rad(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}
/// Radians to degrees.
constexpr double rad_to_deg(double radians) {
  return radians * 180.0 / std::numbers::pi;
}
/// Kilograms to tonnes (display only).
constexpr double kg_to_t(double kg) {
  return kg / 1000.0;
}
/// Metres per second to metres per minute (crane catalogues quote m/min).
constexpr double mps_to_m_per_min(double mps) {
  return mps * 60.0;
}

}  // namespace harbour::core
