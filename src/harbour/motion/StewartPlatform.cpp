#include "harbour/motion/StewartPlatform.h"

#include <cmath>
#include <utility>

namespace harbour::motion {
namespace {

// solves A x = b for 6x6 A by Gaussian elimination with partial pivoting; false if singular
bool solve6(std::array<std::array<double, 6>, 6> a, std::array<double, 6> b, std::array<double, 6>& x) {
  for (int c = 0; c < 6; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 6; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    if (std::abs(a[pivot][c]) < 1e-14) return false;
    std::swap(a[c], a[pivot]);
    std::swap(b[c], b[pivot]);
    for (int r = c + 1; r < 6; ++r) {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < 6; ++k)
        a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int r = 5; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < 6; ++k)
      s -= a[r][k] * x[k];
    x[r] = s / a[r][r];
  }
  return true;
}

}  // namespace

ActuatorLengths StewartPlatform::inverse(const PlatformPose& pose) const {
  // l_i = | T + R p_i - b_i |
  const core::Mat3 r = core::Mat3::from_roll_pitch_yaw(pose[kRoll], pose[kPitch], pose[kYaw]);
  const core::Vec3 t{pose[kSurge], pose[kSway], geometry_.neutral_height_m + pose[kHeave]};
  ActuatorLengths lengths;
  for (int i = 0; i < kActuators; ++i)
    lengths[i] = core::length(t + r * geometry_.platform_joints[i] - geometry_.base_joints[i]);
  return lengths;
}

bool StewartPlatform::forward(const ActuatorLengths& lengths, PlatformPose& io_pose, int max_iterations,
                              double tolerance_m) const {
  constexpr double kH = 1e-7;  // central-difference step for the Jacobian [m or rad]
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    const ActuatorLengths now = inverse(io_pose);
    std::array<double, 6> residual;
    double worst = 0.0;
    for (int i = 0; i < 6; ++i) {
      residual[i] = lengths[i] - now[i];
      worst = std::max(worst, std::abs(residual[i]));
    }
    if (worst <= tolerance_m) return true;
    std::array<std::array<double, 6>, 6> jacobian;
    for (int k = 0; k < 6; ++k) {
      PlatformPose plus = io_pose, minus = io_pose;
      plus[k] += kH;
      minus[k] -= kH;
      const ActuatorLengths lp = inverse(plus), lm = inverse(minus);
      for (int i = 0; i < 6; ++i)
        jacobian[i][k] = (lp[i] - lm[i]) / (2 * kH);
    }
    std::array<double, 6> delta{};
    if (!solve6(jacobian, residual, delta)) return false;
    for (int k = 0; k < 6; ++k)
      io_pose[k] += delta[k];
  }
  return false;
}

bool StewartPlatform::reachable(const ActuatorLengths& lengths, double margin_m) const {
  for (double l : lengths)
    if (!(l >= geometry_.min_length_m + margin_m && l <= geometry_.max_length_m - margin_m)) return false;
  return true;
}

double StewartPlatform::largest_reachable_scale(const PlatformPose& pose, double margin_m) const {
  if (reachable(inverse(pose), margin_m)) return 1.0;
  double inside = 0.0, outside = 1.0;
  while (outside - inside > 1e-6) {
    const double mid = 0.5 * (inside + outside);
    (reachable(inverse(pose * mid), margin_m) ? inside : outside) = mid;
  }
  return inside;
}

}  // namespace harbour::motion
