#pragma once

#include "harbour/core/Vec3.h"

namespace harbour::bulk {

/// A clamshell grab as the bulk model sees it (§3.1.3), settings.
struct GrabSettings {
  double width_m = 2.4;             ///< [m] W: jaw width along the hinge axis
  double max_opening_m = 3.6;       ///< [m] w when fully open, across the hinge axis
  double max_depth_m = 1.2;         ///< [m] d: deepest cut of a bite, and how far the jaw tips swing down
                                    ///< on their arc below the jaws' reference from open to shut
  double sinking_speed_mps = 0.25;  ///< [m/s] v: speed the closing jaws cut into material
  double spill_speed_mps = 2.0;     ///< [m/s] v0: speed material leaves an open grab
  double capacity_m3 = 12.0;        ///< [m^3] struck volume
  double closing_time_s = 6.0;      ///< [s] fully open to closed with the closing winch at full speed
};

/// What the machine does with the grab this step.
struct GrabCommand {
  core::Pose pose;        ///< jaw-tip centre in the world; x across the jaws, y along the hinge, z up
  core::Vec3 velocity;    ///< [m/s] world velocity of the jaw-tip centre
  double close_rate = 0;  ///< [-] +1 closes at full speed, -1 opens, 0 holds
};

/// Mutable state of a grab.
struct GrabState {
  core::Pose pose;
  core::Vec3 velocity;
  double opening_m = 0.0;       ///< [m] current jaw opening w
  double load_m3 = 0.0;         ///< [m^3] material held
  double cut_depth_m = 0.0;     ///< [m] depth the jaws have cut in this bite
  double held_opening_m = 0.0;  ///< [m] the narrowest opening since it took its load (the load fills it)
  bool digging = false;         ///< jaws closing in contact with material this step
};

}  // namespace harbour::bulk
