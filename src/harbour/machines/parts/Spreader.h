#pragma once

#include <array>
#include <cstdint>

#include "harbour/core/StateArchive.h"
#include "harbour/core/Vec3.h"
#include "harbour/physics/PhysicsWorld.h"

namespace harbour::sim {

/// The telescopic spreader's length settings.
enum class SpreaderSize : std::uint8_t { k20ft = 0, k40ft = 1, k45ft = 2 };

/// A size's nominal length in feet (20, 40, 45), as cabs show it.
inline double size_ft(SpreaderSize size) {
  return size == SpreaderSize::k20ft ? 20.0 : size == SpreaderSize::k40ft ? 40.0 : 45.0;
}

/// A telescopic single-lift spreader with four flippers (settings, from the machine file). Lengths follow
/// ISO 668 box lengths, twistlock spans ISO 1161 corner casting centres.
struct SpreaderSettings {
  double mass_kg = 15000.0;                                 ///< [kg] headblock and spreader
  double width_m = 2.438;                                   ///< [m] frame width (a box's width)
  double height_m = 1.0;                                    ///< [m] frame height
  std::array<double, 3> length_m{6.058, 12.192, 13.716};    ///< [m] frame length at 20, 40, 45 ft
  std::array<double, 3> pin_span_m{5.853, 11.985, 13.509};  ///< [m] twistlock centres along the length
  double pin_track_m = 2.259;                               ///< [m] twistlock centres across
  SpreaderSize initial_size = SpreaderSize::k40ft;
  double telescope_speed_mps = 0.2;  ///< [m/s] each end (20 to 40 ft in about 15 s; assumed)
  double flipper_time_s = 3.0;       ///< [s] a flipper's swing up or down (assumed)
  double flipper_depth_m = 0.4;      ///< [m] how far a lowered flipper reaches below the frame
  double flipper_flare_rad = 0.35;   ///< [rad] outward lean of a lowered flipper (its capture funnel)
  double flipper_gap_m = 0.015;      ///< [m] a lowered flipper's inner top edge off the box's face
  double flipper_arm_m = 0.5;        ///< [m] each leg of a flipper's L along the box's end and side
};

/// What the spreader's frame shows the operator and the image generator.
struct SpreaderState {
  SpreaderSize size = SpreaderSize::k40ft;  ///< the selected setting (the target while telescoping)
  double length_m = 0.0;                    ///< [m] frame length now
  bool telescoping = false;
  std::array<double, 4> flippers{};  ///< 0 up, 1 down, per twistlock corner
};

/// The spreader's frame on its physics body: telescoping between the 20/40/45 ft settings (refused while
/// landed or locked), and four flippers at the corners that fold down to funnel the frame onto a box's
/// corners. A flipper is an L of two plates leaning outward; it touches things only when fully down (its
/// swing itself is not simulated). Frames: the body's x across the spreader, y along its length, z up;
/// corner c sits at twistlock corner c (see landed_corners).
class Spreader {
 public:
  Spreader(physics::PhysicsWorld& world, physics::BodyId body, int surface_frame, int surface_flipper,
           const SpreaderSettings& settings);

  /// One control step. `size_button` is a setting button pressed (or none); `flipper_down` the four flipper
  /// switches; telescoping waits while `landed_or_locked`.
  void step(const SpreaderSize* size_button, const std::array<bool, 4>& flipper_down, bool landed_or_locked,
            double dt_s);

  /// Twistlock centres from the frame centre: half the span along the length, half the track across.
  double pin_half_length_m() const { return pin_half_span_; }
  double pin_half_width_m() const { return 0.5 * settings_.pin_track_m; }
  /// The frame's half extents now (x across, y along, z up).
  core::Vec3 half_extents_m() const;
  SpreaderState state() const;
  const SpreaderSettings& settings() const { return settings_; }
  void save_state(core::StateWriter& out) const;
  void restore_state(core::StateReader& in);

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar(self.size_, self.pin_half_span_, self.flippers_);
  }
  void apply_shapes();

  physics::PhysicsWorld& world_;
  SpreaderSettings settings_;
  physics::ShapeId frame_shape_;
  std::array<std::array<physics::ShapeId, 2>, 4> flipper_shapes_{};  // end plate, side plate per corner
  SpreaderSize size_;
  double pin_half_span_ = 0.0;
  std::array<double, 4> flippers_{};
  bool shapes_stale_ = true;
};

}  // namespace harbour::sim
