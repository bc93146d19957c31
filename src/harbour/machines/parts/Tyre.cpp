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
  const double brake = std::max(0.0, command.brake_torque_nm) / tyre.radius_m;
  if (brake > 0.0 && std::abs(forward_mps) < tyre.creep_speed_mps &&
      std::abs(sideways_mps) < tyre.creep_speed_mps) {
    // braked and standing: static friction, the brake holding the wheel and the grip holding it across
    f.held = true;
    f.hold_along_n = std::min(brake + tyre.rolling_resistance * f.normal_n, limit);  // rolling away: both
    f.hold_across_n = limit;
    f.longitudinal_n = command.drive_torque_nm / tyre.radius_m;  // a drive against the brake, held too
    f.drive_n = f.longitudinal_n;
    return f;
  }
  const double creep = std::max(std::abs(forward_mps), tyre.creep_speed_mps);
  // along: the drive at the contact, rolling resistance and the brake against the rolling (both fading in
  // over the creep speed, so a wheel at rest is held, not flicked to and fro)
  const double rolling = std::clamp(forward_mps / tyre.creep_speed_mps, -1.0, 1.0);
  double drive = command.drive_torque_nm / tyre.radius_m;
  double along = drive - tyre.rolling_resistance * f.normal_n * rolling;
  along -= std::min(brake, limit) * rolling;
  if (brake > limit && std::abs(forward_mps) > tyre.creep_speed_mps) f.sliding = true;  // locked
  // across: the slip angle's force
  const double across = -tyre.cornering_stiffness_n_per_rad * std::atan2(sideways_mps, creep);
  const double total = std::hypot(along, across);
  if (total > limit) {
    const double scale = limit / total;
    along *= scale;
    drive *= scale;
    f.sliding = true;
    f.lateral_n = across * scale;
  } else {
    f.lateral_n = across;
  }
  f.longitudinal_n = along;
  f.drive_n = drive;
  return f;
}

TyreForces apply_tyre(physics::PhysicsWorld& world, physics::BodyId body, const core::Vec3& hub_m,
                      const TyreSettings& tyre, const TyreCommand& command, const Ground& ground) {
  const core::Pose pose = world.pose(body);
  const core::Vec3 hub = pose.to_parent(hub_m);
  const GroundContact g = ground.at(hub.x, hub.y);
  const core::Vec3 n = g.normal;
  // the wheel's lowest point toward the ground and how far it is pressed into it, along the normal
  const core::Vec3 on_ground{hub.x, hub.y, g.z_m};
  const double sag = dot(on_ground - (hub - n * tyre.radius_m), n);
  if (sag <= 0.0) return {};
  const core::Vec3 contact = hub - n * (tyre.radius_m - sag);
  // the wheel's heading along the ground: the body's x turned by the steering about the body's z, in the
  // plane
  const core::Vec3 heading_body{std::cos(command.steer_rad), std::sin(command.steer_rad), 0.0};
  core::Vec3 heading = pose.rotation * heading_body;
  heading = heading - n * dot(heading, n);
  const double length = std::sqrt(dot(heading, heading));
  if (length < 1e-9) return {};
  heading = heading * (1.0 / length);
  const core::Vec3 left = cross(n, heading);
  const core::Vec3 v = world.point_velocity(body, pose.to_local(contact));
  TyreSettings gripping = tyre;
  gripping.friction *= g.grip;
  TyreForces f =
      tyre_forces(gripping, command, sag, g.rise_mps * n.z - dot(v, n), dot(v, heading), dot(v, left));
  f.drive_power_w = f.drive_n * dot(v, heading);
  world.add_force_at(body, contact, n * f.normal_n + heading * f.longitudinal_n + left * f.lateral_n);
  if (f.held) world.hold_point(body, contact, n, heading, f.hold_along_n, f.hold_across_n);
  return f;
}

}  // namespace harbour::sim
