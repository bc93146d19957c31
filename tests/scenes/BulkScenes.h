#pragma once

// Scenes shared by tests and benchmarks (Box2D style): the same setup measured and checked.

#include <cmath>

#include "harbour/bulk/BulkWorld.h"
#include "harbour/core/Units.h"

namespace harbour::scenes {

/// A coal-like material with a given angle of repose [deg].
inline bulk::Material test_material(double repose_deg = 35.0, double flow_fraction = 0.5) {
  bulk::Material m;
  m.name = "test";
  m.bulk_density_kg_m3 = 1000.0;
  m.angle_of_repose_rad = core::deg_to_rad(repose_deg);
  m.flow_fraction = flow_fraction;
  m.compression_gain = 4.0;
  return m;
}

/// Pours `volume_m3` at the centre of `grid` at `rate_m3_per_step`, then relaxes until the active list
/// empties (or `max_relax_steps`). Returns the number of steps run.
inline int pour_heap(bulk::HeightGrid& grid, double volume_m3, double rate_m3_per_step,
                     int max_relax_steps = 200000) {
  const int ci = grid.cells_x() / 2, cj = grid.cells_y() / 2;
  int steps = 0;
  for (double poured = 0.0; poured < volume_m3; poured += rate_m3_per_step, ++steps) {
    grid.add_volume(ci, cj, std::min(rate_m3_per_step, volume_m3 - poured));
    grid.relax_active();
  }
  for (int n = 0; n < max_relax_steps && grid.active_count() > 0; ++n, ++steps)
    grid.relax_active();
  return steps;
}

/// A grab command at world point `at`, jaws along the grid axes.
inline bulk::GrabCommand grab_at(const core::Vec3& at, double close_rate) {
  bulk::GrabCommand c;
  c.pose.position = at;
  c.close_rate = close_rate;
  return c;
}

}  // namespace harbour::scenes
