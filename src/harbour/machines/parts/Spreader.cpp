#include "harbour/machines/parts/Spreader.h"

#include <algorithm>
#include <cmath>

namespace harbour::sim {
namespace {

constexpr double kFlipperPlate_m = 0.04;  // plate thickness
// twistlock corner c's signs (along the length, across) as in landed_corners
constexpr double kCornerSign[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};

std::size_t index(SpreaderSize size) {
  return static_cast<std::size_t>(size);
}

// a plate whose inner top edge (local `edge`) sits at `target` when turned by `rotation`
core::Pose plate_pose(const core::Mat3& rotation, const core::Vec3& edge, const core::Vec3& target) {
  return {rotation, target - rotation * edge};
}

}  // namespace

Spreader::Spreader(physics::PhysicsWorld& world, physics::BodyId body, int surface_frame, int surface_flipper,
                   const SpreaderSettings& settings)
    : world_(world),
      settings_(settings),
      size_(settings.initial_size),
      pin_half_span_(0.5 * settings.pin_span_m[index(settings.initial_size)]) {
  frame_shape_ = world.add_box_shape(body, half_extents_m(), {}, surface_frame);
  for (auto& corner : flipper_shapes_)
    for (physics::ShapeId& plate : corner)
      plate = world.add_box_shape(body, {0.1, 0.1, 0.1}, {}, surface_flipper);
  apply_shapes();
}

core::Vec3 Spreader::half_extents_m() const {
  const std::size_t k = index(size_);
  const double overhang = 0.5 * (settings_.length_m[k] - settings_.pin_span_m[k]);  // casting to box end
  return {0.5 * settings_.width_m, pin_half_span_ + overhang, 0.5 * settings_.height_m};
}

void Spreader::step(const SpreaderSize* size_button, const std::array<bool, 4>& flipper_down,
                    bool landed_or_locked, double dt_s) {
  if (size_button && *size_button != size_) {
    size_ = *size_button;
    shapes_stale_ = true;
  }
  const double target = 0.5 * settings_.pin_span_m[index(size_)];
  if (!landed_or_locked && pin_half_span_ != target) {
    const double stroke = settings_.telescope_speed_mps * dt_s;
    pin_half_span_ += std::clamp(target - pin_half_span_, -stroke, stroke);
    shapes_stale_ = true;
  }
  for (std::size_t c = 0; c < 4; ++c) {
    const double swing = dt_s / settings_.flipper_time_s;
    const double was = flippers_[c];
    flippers_[c] = std::clamp(flippers_[c] + (flipper_down[c] ? swing : -swing), 0.0, 1.0);
    if ((was == 1.0) != (flippers_[c] == 1.0)) shapes_stale_ = true;
  }
  if (shapes_stale_) apply_shapes();
}

void Spreader::apply_shapes() {
  const core::Vec3 h = half_extents_m();
  world_.set_box_shape(frame_shape_, h, {});
  const double g = settings_.flipper_gap_m, a = settings_.flipper_arm_m, t = kFlipperPlate_m,
               lean = settings_.flipper_flare_rad;
  const core::Vec3 plate_end{0.5 * a, 0.5 * t, 0.5 * settings_.flipper_depth_m};
  const core::Vec3 plate_side{0.5 * t, 0.5 * a, 0.5 * settings_.flipper_depth_m};
  for (std::size_t c = 0; c < 4; ++c) {
    // twistlock frame (x along, y across) to body frame: along is body +y, across is body -x
    const double ys = kCornerSign[c][0], xs = -kCornerSign[c][1];
    const core::Pose end =
        plate_pose(core::Mat3::rotation({1, 0, 0}, ys * lean), {0, -ys * 0.5 * t, plate_end.z},
                   {xs * (h.x + g + t - 0.5 * a), ys * (h.y + g), -h.z});
    const core::Pose side =
        plate_pose(core::Mat3::rotation({0, 1, 0}, -xs * lean), {-xs * 0.5 * t, 0, plate_side.z},
                   {xs * (h.x + g), ys * (h.y + g + t - 0.5 * a), -h.z});
    world_.set_box_shape(flipper_shapes_[c][0], plate_end, end);
    world_.set_box_shape(flipper_shapes_[c][1], plate_side, side);
    for (const physics::ShapeId plate : flipper_shapes_[c])
      world_.set_shape_enabled(plate, flippers_[c] == 1.0);
  }
  shapes_stale_ = false;
}

SpreaderState Spreader::state() const {
  return {size_, 2.0 * half_extents_m().y, pin_half_span_ != 0.5 * settings_.pin_span_m[index(size_)],
          flippers_};
}

void Spreader::save_state(core::StateWriter& out) const {
  archive(*this, out);
}

void Spreader::restore_state(core::StateReader& in) {
  archive(*this, in);
  apply_shapes();
}

}  // namespace harbour::sim
