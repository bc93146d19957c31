#pragma once

#include "harbour/core/Vec3.h"
#include "harbour/physics/PhysicsWorld.h"
#include "harbour/sim/Ground.h"

namespace harbour::sim {

/// A pneumatic tyre as data: its vertical spring, its cornering stiffness, rolling resistance and the
/// friction it has on the ground (settings; values for large off-road tyres on dry concrete are assumed
/// unless a machine file gives them).
struct TyreSettings {
  double radius_m = 0.8;
  double vertical_stiffness_n_per_m = 2.0e6;     ///< [N/m] the tyre's spring under its load
  double vertical_damping_ns_per_m = 4.0e4;      ///< [N s/m]
  double cornering_stiffness_n_per_rad = 4.0e5;  ///< [N/rad] lateral force per slip angle at small angles
  double rolling_resistance = 0.015;             ///< [-] resistance over load while rolling
  double friction = 0.8;                         ///< [-] road friction coefficient: the most force over load
  double creep_speed_mps = 0.2;  ///< [m/s] below this speed the slip is measured against it (standing)
};

/// What acts on a wheel this step: where it points, the drive torque at its axle and its brake.
struct TyreCommand {
  double steer_rad = 0.0;        ///< wheel heading from the body's x, about the body's z
  double drive_torque_nm = 0.0;  ///< [N m] + drives forward (along the wheel's heading)
  double brake_torque_nm = 0.0;  ///< [N m] the most the brake holds (>= 0)
};

/// The forces a tyre passes to the ground this step, in the world [N], and how it grips.
struct TyreForces {
  double normal_n = 0.0;        ///< [N] the ground's push on it (0: off the ground)
  double longitudinal_n = 0.0;  ///< [N] along its heading (+ forward)
  double lateral_n = 0.0;       ///< [N] across it (+ to its left)
  double drive_n = 0.0;         ///< [N] the drive's part of longitudinal_n (what the friction circle left)
  double drive_power_w = 0.0;   ///< [W] the drive's force times the contact's speed along the heading
  bool sliding = false;         ///< the friction circle limits it (a locked or spinning wheel, a skid)
  /// Braked and standing (slower than the creep speed both ways): static friction holds the contact, a
  /// constraint of at most these forces (brake and rolling resistance along, the grip across) instead of the
  /// two above
  bool held = false;
  double hold_along_n = 0.0, hold_across_n = 0.0;
};

/// A tyre's forces from its contact's state (a pure function): the vertical spring-damper on the compression
/// `sag_m` (and its rate); the drive or the brake along the heading, a locked brake sliding at µ·Fz; rolling
/// resistance against the rolling; a lateral force −Cα·α with the slip angle α from the contact's velocity
/// across and along the heading (measured against at least the creep speed); both together limited to µ·Fz
/// (the friction circle). A braked tyre slower than the creep speed is held instead (TyreForces::held): it
/// stays put up to its brake along and its grip across, and slides at those forces beyond them.
TyreForces tyre_forces(const TyreSettings& tyre, const TyreCommand& command, double sag_m,
                       double sag_rate_mps, double forward_mps, double sideways_mps);

/// Pushes on `body` what a tyre on `ground` passes it this step: the wheel's centre at `hub_m` (body frame),
/// the body's z up. The ground is the plane under the hub: the tyre presses along its normal, its heading
/// runs along it, its sag rate counts the ground's rise; a held tyre's contact is held by
/// PhysicsWorld::hold_point. Returns its forces.
TyreForces apply_tyre(physics::PhysicsWorld& world, physics::BodyId body, const core::Vec3& hub_m,
                      const TyreSettings& tyre, const TyreCommand& command, const Ground& ground);

}  // namespace harbour::sim
