#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harbour/bulk/BulkWorld.h"

namespace harbour::bulk {

/// A grid placed in a scene (settings): a yard pile's area, a hopper, a moored vessel's rolling hold.
struct GridPlacement {
  std::string name;
  GridSettings settings;
  double origin_x_m = 0, origin_y_m = 0, origin_z_m = 0;  ///< [m] world position of the grid corner
  double yaw_rad = 0;                                     ///< [rad] about world z
  double roll_amplitude_rad = 0;                          ///< [rad] rolling about the grid's centre line
  double roll_period_s = 0;                               ///< [s] 0: no motion
  double outflow_m3_per_s = 0;  ///< [m^3/s] a hopper: what is in it leaves through its outlet (delivered)
  double fill_m = 0;            ///< [m] filled level to this depth at the start
  bool on_vessel = false;       ///< origin and yaw are in the vessel's frame: the grid moves with the vessel
  /// Its pose at time `t_s` (turned by the yaw, rolling about its centre line along x) and the velocities of
  /// its frame's origin and of its turning.
  core::Pose pose_at(double t_s, core::Vec3& linear_velocity, core::Vec3& angular_velocity) const;
};

/// An initial heap: a cone at the angle of repose.
struct HeapPlacement {
  int grid = 0;
  double x_m = 0, y_m = 0;  ///< [m] centre, grid frame
  double volume_m3 = 0;
};

/// The bulk material of a scene (settings): one material, its grids and initial heaps.
struct BulkScene {
  Material material;
  double spill_level_m = 0;  ///< [m] falling material below this outside every grid is spilled
  std::vector<GridPlacement> grids;
  std::vector<HeapPlacement> heaps;
};

/// A moving frame grids ride on (the moored vessel): its pose and the velocities of its origin.
struct CarrierMotion {
  core::Pose frame;
  core::Vec3 linear_velocity, angular_velocity;
};

/// The scene's world: its grids at their poses at time 0 (those on the vessel on `vessel`), their fills and
/// its heaps.
std::unique_ptr<BulkWorld> build_bulk_world(const BulkScene& scene, const CarrierMotion& vessel = {});
/// Moves the rolling grids to time `t_s`, and those on the vessel with it.
void move_grids(BulkWorld& world, const BulkScene& scene, double t_s, const CarrierMotion& vessel = {});

}  // namespace harbour::bulk
