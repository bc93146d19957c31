#pragma once

#include <span>

#include "harbour/core/Vec3.h"

namespace harbour::bulk {

/// Penalty contact between a rigid body's contact points and bulk material (§3.1.2), per point.
struct ContactSettings {
  double stiffness_n_per_m = 2.0e5;  ///< [N/m] linear spring on penetration depth
  double damping_n_s_per_m = 2.0e4;  ///< [N s/m] damper on penetration rate (highly damped)
};

/// A body touching the material: its pose, velocity and contact points in its own frame.
struct ContactBody {
  core::Pose pose;                     ///< body frame in the world
  core::Vec3 linear_velocity;          ///< [m/s] of the body origin, world frame
  core::Vec3 angular_velocity;         ///< [rad/s] world frame
  std::span<const core::Vec3> points;  ///< [m] contact points in the body frame
};

/// Resultant of the penalty forces on one body: apply `force` at `point` (all forces share one normal).
struct ContactResult {
  core::Vec3 force;  ///< [N] world frame
  core::Vec3 point;  ///< [m] world application point (force-weighted centroid)
  int points_in_contact = 0;
  double max_penetration_m = 0.0;  ///< [m]
};

}  // namespace harbour::bulk
