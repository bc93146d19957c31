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

std::unique_ptr<BulkWorld> build_bulk_world(const BulkScene& scene) {
  BulkWorldSettings settings;
  settings.spill_level_m = scene.spill_level_m;
  auto world = std::make_unique<BulkWorld>(scene.material, settings);
  for (const GridPlacement& g : scene.grids) {
    core::Vec3 v, w;
    const int id = world->add_grid(g.settings, g.pose_at(0.0, v, w));
    world->set_outflow(id, g.outflow_m3_per_s);
  }
  for (const HeapPlacement& h : scene.heaps)
    world->add_heap(h.grid, h.x_m, h.y_m, h.volume_m3);
  return world;
}

void move_grids(BulkWorld& world, const BulkScene& scene, double t_s) {
  for (std::size_t n = 0; n < scene.grids.size(); ++n) {
    const GridPlacement& g = scene.grids[n];
    if (g.roll_period_s <= 0.0) continue;
    core::Vec3 v, w;
    const core::Pose pose = g.pose_at(t_s, v, w);
    world.grid(static_cast<int>(n)).set_pose(pose, v, w);
  }
}

}  // namespace harbour::bulk
