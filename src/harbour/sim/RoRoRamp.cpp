#include "harbour/sim/RoRoRamp.h"

#include <cmath>
#include <numbers>

namespace harbour::sim {

void RoRoRamp::move_to(double time_s) {
  deck_height_m_ = settings_.deck_height_m;
  deck_rise_mps_ = 0.0;
  for (const Harmonic& h : {settings_.tide, settings_.heave}) {
    const double w = 2.0 * std::numbers::pi / h.period_s;
    deck_height_m_ += h.amplitude * std::sin(w * time_s + h.phase_rad);
    deck_rise_mps_ += h.amplitude * w * std::cos(w * time_s + h.phase_rad);
  }
}

double RoRoRamp::slope_rad() const {
  return std::atan2(deck_height_m_, settings_.length_m);
}

GroundContact RoRoRamp::at(double x_m, double y_m) const {
  // along the ramp from its toe and across it
  const RampSettings& s = settings_;
  const double c = std::cos(s.heading_rad), sn = std::sin(s.heading_rad);
  const double dx = x_m - s.toe_m.x, dy = y_m - s.toe_m.y;
  const double along = dx * c + dy * sn, across = -dx * sn + dy * c;
  const double quay = s.toe_m.z;
  if (std::abs(across) > s.width_m / 2 || along < 0.0 || along > s.length_m + s.deck_length_m)
    return {quay, {0, 0, 1}, 0.0, 1.0};
  if (along > s.length_m) return {quay + deck_height_m_, {0, 0, 1}, deck_rise_mps_, s.grip};
  const double slope = slope_rad();
  const core::Vec3 normal{-std::sin(slope) * c, -std::sin(slope) * sn, std::cos(slope)};
  return {quay + deck_height_m_ * along / s.length_m, normal, deck_rise_mps_ * along / s.length_m, s.grip};
}

core::Pose RoRoRamp::ramp_pose() const {
  // the plate's top on the ramp's surface, half way up
  const RampSettings& s = settings_;
  const double slope = slope_rad();
  const core::Mat3 rotation =
      core::Mat3::rotation({0, 0, 1}, s.heading_rad) * core::Mat3::rotation({0, 1, 0}, -slope);
  const core::Vec3 middle =
      s.toe_m + core::Vec3{std::cos(s.heading_rad), std::sin(s.heading_rad), 0.0} * (s.length_m / 2) +
      core::Vec3{0, 0, deck_height_m_ / 2};
  return {rotation, middle - rotation * core::Vec3{0, 0, kPlate_m / 2}};
}

core::Vec3 RoRoRamp::ramp_half_extents_m() const {
  const double run = std::hypot(settings_.length_m, deck_height_m_);
  return {run / 2, settings_.width_m / 2, kPlate_m / 2};
}

core::Pose RoRoRamp::deck_pose() const {
  const RampSettings& s = settings_;
  const core::Vec3 middle =
      s.toe_m +
      core::Vec3{std::cos(s.heading_rad), std::sin(s.heading_rad), 0.0} * (s.length_m + s.deck_length_m / 2) +
      core::Vec3{0, 0, deck_height_m_ - kPlate_m / 2};
  return {core::Mat3::rotation({0, 0, 1}, s.heading_rad), middle};
}

core::Vec3 RoRoRamp::deck_half_extents_m() const {
  return {settings_.deck_length_m / 2, settings_.width_m / 2, kPlate_m / 2};
}

}  // namespace harbour::sim
