#include "harbour/bulk/BulkScene.h"

#include <cmath>
#include <numbers>

namespace harbour::bulk {

core::Pose GridPlacement::pose_at(double t_s, core::Vec3& linear_velocity,
                                  core::Vec3& angular_velocity) const {
  const core::Mat3 yaw = core::Mat3::rotation({0, 0, 1}, yaw_rad);
  const core::Vec3 origin{origin_x_m, origin_y_m, origin_z_m};
  core::Pose pose{yaw, origin};
  linear_velocity = {};
  angular_velocity = {};
  if (roll_period_s <= 0.0) return pose;
  // rolling about the grid's centre line along its x
  const double w = 2.0 * std::numbers::pi / roll_period_s;
  const double roll = roll_amplitude_rad * std::sin(w * t_s),
               roll_rate = roll_amplitude_rad * w * std::cos(w * t_s);
  const core::Vec3 centre_line{0.0, 0.5 * settings.cells_y * settings.cell_size_m, 0.0};
  pose.rotation = yaw * core::Mat3::rotation({1, 0, 0}, roll);
  const core::Vec3 axis_point = origin + yaw * centre_line;
  pose.position = axis_point - pose.rotation * centre_line;
  angular_velocity = yaw * core::Vec3{roll_rate, 0, 0};
  linear_velocity = cross(angular_velocity, pose.position - axis_point);
  return pose;
}

namespace {

// a grid's pose and velocities riding on the vessel's frame
core::Pose on_carrier(const GridPlacement& g, const CarrierMotion& vessel, core::Vec3& v, core::Vec3& w) {
  core::Vec3 unused_v, unused_w;
  const core::Pose local = g.pose_at(0.0, unused_v, unused_w);
  const core::Pose pose{vessel.frame.rotation * local.rotation, vessel.frame.to_parent(local.position)};
  w = vessel.angular_velocity;
  v = vessel.linear_velocity + cross(w, pose.position - vessel.frame.position);
  return pose;
}

}  // namespace

std::unique_ptr<BulkWorld> build_bulk_world(const BulkScene& scene, const CarrierMotion& vessel) {
  BulkWorldSettings settings;
  settings.spill_level_m = scene.spill_level_m;
  auto world = std::make_unique<BulkWorld>(scene.material, settings);
  for (const GridPlacement& g : scene.grids) {
    core::Vec3 v, w;
    const int id =
        world->add_grid(g.settings, g.on_vessel ? on_carrier(g, vessel, v, w) : g.pose_at(0.0, v, w));
    world->set_outflow(id, g.outflow_m3_per_s);
    if (g.fill_m > 0.0) world->fill_level(id, g.fill_m);
  }
  for (const HeapPlacement& h : scene.heaps)
    world->add_heap(h.grid, h.x_m, h.y_m, h.volume_m3);
  return world;
}

void move_grids(BulkWorld& world, const BulkScene& scene, double t_s, const CarrierMotion& vessel) {
  for (std::size_t n = 0; n < scene.grids.size(); ++n) {
    const GridPlacement& g = scene.grids[n];
    core::Vec3 v, w;
    if (g.on_vessel)
      world.grid(static_cast<int>(n)).set_pose(on_carrier(g, vessel, v, w), v, w);
    else if (g.roll_period_s > 0.0)
      world.grid(static_cast<int>(n)).set_pose(g.pose_at(t_s, v, w), v, w);
  }
}

}  // namespace harbour::bulk
