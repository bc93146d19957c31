#pragma once

// Scenes shared by tests and benchmarks (Box2D style): the same setup measured and checked.

#include <algorithm>
#include <cmath>

#include "harbour/bulk/BulkWorld.h"
#include "harbour/core/Units.h"

namespace harbour::scenes {

using bulk::BulkWorld;
using bulk::BulkWorldSettings;
using bulk::GrabCommand;
using bulk::GrabSettings;
using bulk::HeightGrid;

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

/// A local grab dig on a large yard grid: a 1000 m^3 coal heap in the middle of an n x n grid of
/// 10 cm cells; the grab bites at the heap's flank for 6 s, lifts 2 m and dumps back for 2 s, in a loop.
/// The benchmark measures it with the active list and with the full sweep (BulkWorld::use_full_sweep).
struct DigScene {
  explicit DigScene(int cells) : world(test_material(35.0), BulkWorldSettings{}) {
    grid = world.add_grid({cells, cells, 0.1}, {});
    centre = 0.05 * cells;
    world.add_heap(grid, centre, centre, 1000.0);
    grab = world.add_grab(GrabSettings{});
    for (int n = 0; n < 100000 && world.grid(grid).active_count() > 0; ++n)
      world.grid(grid).relax_active();
  }

  void step() {
    const long phase = steps++ % 8000;
    const double x = centre + 3.0, y = centre;
    const HeightGrid& g = world.grid(grid);
    if (phase == 0) command = grab_at({x, y, g.surface_height(x, y)}, 1.0);
    if (phase < 6000) {
      if (world.grab(grab).digging)
        command.pose.position.z -= world.grab_settings(grab).sinking_speed_mps * 0.001;
    } else {
      command.pose.position.z = g.surface_height(x, y) + 2.0;
      command.close_rate = -1.0;
    }
    world.step(0.001, {&command, 1});
  }

  BulkWorld world;
  int grid = 0, grab = 0;
  double centre = 0;
  long steps = 0;
  GrabCommand command;
};

}  // namespace harbour::scenes
