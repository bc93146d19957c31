#pragma once

#include <string>
#include <vector>

#include "harbour/core/Vec3.h"

namespace harbour::cable {

/// Where an element sits: a point on a body (body index into CableBodies), or fixed in the world (body -1).
struct Mount {
  int body = -1;
  core::Vec3 local;  ///< [m] in the body frame (world frame when body is -1)
};

/// Steel wire rope (settings).
struct RopeSettings {
  std::string name;
  double diameter_m = 0.028;              ///< [m]
  double mass_per_m_kg = 2.70;            ///< [kg/m]
  double axial_stiffness_n = 3.1e7;       ///< [N] EA on the metallic area
  double min_breaking_force_n = 461e3;    ///< [N]
  double safety_factor = 5.0;             ///< [-] working load limit = MBF / safety factor (EN 12385-4)
  double axial_damping_s = 0.002;         ///< [s] strain-rate damping: tension += EA * this * strain rate
  double transverse_damping_per_s = 0.3;  ///< [1/s] damping of the transverse oscillation
  /// [-] share of the tension lost by the rope's bending hysteresis where a length of it bends onto or
  /// straightens off a sheave or drum: half of the 2 % per sheave passage of steel wire rope (verope
  /// Tech-Info 09.4; the bearings' part is ~0.1 %, Feyrer, Wire Ropes, 2nd ed. 2015, eq. 3.100)
  double bending_loss = 0.01;
  int nodes = 12;         ///< intervals per segment for the wave equation
  std::vector<int> path;  ///< element indices: a drum first, then sheaves, then an anchor or drum
};

enum class ElementKind { kDrum, kSheave, kAnchor };

/// A drum, sheave or anchor (settings).
struct ElementSettings {
  std::string name;
  ElementKind kind = ElementKind::kAnchor;
  Mount mount;
  double radius_m = 0.0;                    ///< [m] pitch radius (drum, sheave)
  double inertia_kg_m2 = 0.0;               ///< [kg m^2] (drum with motor and gearing reflected, sheave)
  double friction_torque_n_m = 0.0;         ///< [N m] bearing friction (sheave)
  double max_rope_speed_mps = 0.0;          ///< [m/s] drum: rope speed at full command
  double max_rope_acceleration_mps2 = 0.0;  ///< [m/s^2] drum: speed ramp
  double max_torque_n_m = 0.0;              ///< [N m] drum motor torque limit
  double brake_torque_n_m = 0.0;            ///< [N m] drum holding brake
  double stored_rope_m = 0.0;               ///< [m] drum: rope wound on it at the start, per rope
};

/// A whole reeving: elements and the ropes that run through them (settings, loaded from data/reeving/).
struct ReevingSettings {
  std::string name;
  std::vector<ElementSettings> elements;
  std::vector<RopeSettings> ropes;
  int max_substeps = 8;          ///< wave sub-steps per simulation step before a segment becomes a spring
  double resume_fraction = 0.8;  ///< a spring segment oscillates again below this share of the switch tension
  /// The rope stretched along its chord, a spring without the rope's inertia, pretension without sag: the
  /// model every run recorded without recording header flag bit 1 ran on (their replays run on it; never from
  /// a file).
  bool stretch_along_chord = false;
  /// The wave's transverse damping acts against the ground instead of between the rope and its ends: the
  /// model every run recorded without recording header flag bit 4 ran on (their replays run on it; never from
  /// a file).
  bool damping_against_ground = false;
  /// No bending hysteresis where the ropes turn on their sheaves and drums: the model every run recorded
  /// without recording header flag bit 5 ran on (their replays run on it; never from a file).
  bool sheaves_without_bending_loss = false;
  /// The sheaves as every run recorded without recording header flag bit 7 ran (their replays run so; never
  /// from a file): each sheave's speed balances the tensions after the step's rope transfer (which held the
  /// span before a sheave above the one after while hoisting), the rope loses nothing running over it, a
  /// segment's strain rate is its length's alone, and a rope is overloaded the moment it stands above its
  /// working load.
  bool simple_sheaves = false;
  /// A slack segment's shape fades to its chord over kSpringDecay_s, as in every run recorded without
  /// recording header flag bit 8 (their replays run so; never from a file): each slack spell lifted the
  /// rope's sag for nothing, and the next time it drew taut that work went to its ends.
  bool slack_ropes_straighten = false;
};

}  // namespace harbour::cable
