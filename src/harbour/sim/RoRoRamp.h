#pragma once

#include "harbour/core/Vec3.h"
#include "harbour/sim/Ground.h"
#include "harbour/sim/Vessel.h"

namespace harbour::sim {

/// A ro-ro vessel's stern ramp and vehicle deck as the ground vehicles drive on (settings): the ramp rests
/// its toe on the quay and hinges at the vessel's stern; the deck runs on beyond the hinge at the hinge's
/// height, which rises and falls with the tide and the swell, and the ramp's slope with it.
struct RampSettings {
  core::Vec3 toe_m;             ///< [m] the middle of the ramp's toe on the quay
  double heading_rad = 0.0;     ///< up the ramp, toward the vessel
  double length_m = 18.0;       ///< [m] toe to hinge, horizontally
  double width_m = 8.0;         ///< [m] the ramp's and the deck's
  double deck_length_m = 40.0;  ///< [m] the vehicle deck beyond the hinge
  double deck_height_m = 1.8;   ///< [m] the hinge over the quay at mean tide in still water
  Harmonic tide;                ///< [m] the deck's slow rise and fall
  Harmonic heave;               ///< [m] the vessel in the swell
  double grip = 1.0;            ///< the ramp's and deck's friction over the quay's (a wet steel ramp: less)
};

/// The quay with a stern ramp and deck on it, at a moment (a pure function of time: nothing to save).
class RoRoRamp final : public Ground {
 public:
  explicit RoRoRamp(const RampSettings& settings) : settings_(settings) {}
  /// The deck's height and speed at `time_s`.
  void move_to(double time_s);
  GroundContact at(double x_m, double y_m) const override;

  double deck_height_m() const { return deck_height_m_; }
  /// The ramp's slope now [rad].
  double slope_rad() const;
  /// The ramp's and deck's plates as boxes (centre pose, half extents), for drawing.
  core::Pose ramp_pose() const;
  core::Vec3 ramp_half_extents_m() const;
  core::Pose deck_pose() const;
  core::Vec3 deck_half_extents_m() const;
  const RampSettings& settings() const { return settings_; }

 private:
  static constexpr double kPlate_m = 0.3;  // the plates' thickness, drawn below the surface
  RampSettings settings_;
  double deck_height_m_ = 0.0, deck_rise_mps_ = 0.0;
};

}  // namespace harbour::sim
