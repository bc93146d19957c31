#include "harbour/machines/parts/Tyre.h"

#include <algorithm>
#include <cmath>

namespace harbour::sim {

TyreForces tyre_forces(const TyreSettings& tyre, const TyreCommand& command, double sag_m,
                       double sag_rate_mps, double forward_mps, double sideways_mps) {
  TyreForces f;
  if (sag_m <= 0.0) return f;  // off the ground
  f.normal_n =
      std::max(0.0, tyre.vertical_stiffness_n_per_m * sag_m + tyre.vertical_damping_ns_per_m * sag_rate_mps);
  const double limit = tyre.friction * f.normal_n;
  const double creep = std::max(std::abs(forward_mps), tyre.creep_speed_mps);
  // along: the drive at the contact, rolling resistance and the brake against the rolling (both fading in
  // over the creep speed, so a wheel at rest is held, not flicked to and fro)
  const double rolling = std::clamp(forward_mps / tyre.creep_speed_mps, -1.0, 1.0);
  double along = command.drive_torque_nm / tyre.radius_m - tyre.rolling_resistance * f.normal_n * rolling;
  const double brake = std::max(0.0, command.brake_torque_nm) / tyre.radius_m;
  along -= std::min(brake, limit) * rolling;
  if (brake > limit && std::abs(forward_mps) > tyre.creep_speed_mps) f.sliding = true;  // locked
  // across: the slip angle's force
  const double across = -tyre.cornering_stiffness_n_per_rad * std::atan2(sideways_mps, creep);
  const double total = std::hypot(along, across);
  if (total > limit) {
    const double scale = limit / total;
    along *= scale;
    f.sliding = true;
    f.lateral_n = across * scale;
  } else {
    f.lateral_n = across;
  }
  f.longitudinal_n = along;
  return f;
}

TyreForces apply_tyre(physics::PhysicsWorld& world, physics::BodyId body, const core::Vec3& hub_m,
                      const TyreSettings& tyre, const TyreCommand& command, double ground_z_m) {
  const core::Pose pose = world.pose(body);
  const core::Vec3 hub = pose.to_parent(hub_m);
  const core::Vec3 contact{hub.x, hub.y, ground_z_m};
  const double sag = ground_z_m - (hub.z - tyre.radius_m);
  if (sag <= 0.0) return {};
  // the wheel's heading on the ground: the body's x turned by the steering about the body's z, flattened
  const core::Vec3 heading_body{std::cos(command.steer_rad), std::sin(command.steer_rad), 0.0};
  core::Vec3 heading = pose.rotation * heading_body;
  heading.z = 0.0;
  const double length = std::sqrt(dot(heading, heading));
  if (length < 1e-9) return {};
  heading = heading * (1.0 / length);
  const core::Vec3 left{-heading.y, heading.x, 0.0};
  const core::Vec3 v = world.point_velocity(body, pose.to_local(contact));
  const TyreForces f = tyre_forces(tyre, command, sag, -v.z, dot(v, heading), dot(v, left));
  world.add_force_at(body, contact,
                     core::Vec3{0, 0, f.normal_n} + heading * f.longitudinal_n + left * f.lateral_n);
  return f;
}

}  // namespace harbour::sim
