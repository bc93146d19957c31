#pragma once

#include <array>

namespace harbour::motion {

/// Degrees of freedom of a motion platform, in the cab frame (x forward, y left, z up).
enum Dof : int { kSurge, kSway, kHeave, kRoll, kPitch, kYaw, kDofCount };

/// Platform pose relative to neutral: surge, sway, heave [m]; roll, pitch, yaw [rad] (right-handed about x,
/// y, z; applied as Rz(yaw) Ry(pitch) Rx(roll), so positive pitch is nose down and positive roll is left side
/// up).
struct PlatformPose {
  std::array<double, kDofCount> dof{};

  double& operator[](int i) { return dof[static_cast<std::size_t>(i)]; }
  double operator[](int i) const { return dof[static_cast<std::size_t>(i)]; }
  friend bool operator==(const PlatformPose&, const PlatformPose&) = default;
};

inline PlatformPose operator*(PlatformPose p, double s) {
  for (double& v : p.dof)
    v *= s;
  return p;
}
inline PlatformPose operator+(PlatformPose a, const PlatformPose& b) {
  for (int i = 0; i < kDofCount; ++i)
    a[i] += b[i];
  return a;
}
inline PlatformPose operator-(PlatformPose a, const PlatformPose& b) {
  for (int i = 0; i < kDofCount; ++i)
    a[i] -= b[i];
  return a;
}

}  // namespace harbour::motion
