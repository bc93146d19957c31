#pragma once

// Scenes shared by tests and benchmarks (Box2D style): the same setup measured and checked.

#include <algorithm>
#include <cmath>
#include <vector>

#include "harbour/bulk/BulkWorld.h"
#include "harbour/core/Units.h"

namespace harbour::scenes {

using bulk::BulkWorld;
using bulk::BulkWorldSettings;
using bulk::GrabCommand;
using bulk::GrabSettings;
using bulk::HeightGrid;

/// The flow friction of the shipped materials as a share of their repose angle (data/materials.yaml).
inline constexpr double kFlowShare = 0.85;

/// A coal-like material with a given angle of repose [deg] (flow friction: the shipped share unless given).
inline bulk::Material test_material(double repose_deg = 35.0, double flow_friction_deg = -1.0) {
  bulk::Material m;
  m.name = "test";
  m.bulk_density_kg_m3 = 1000.0;
  m.angle_of_repose_rad = core::deg_to_rad(repose_deg);
  m.flow_friction_rad =
      core::deg_to_rad(flow_friction_deg > 0.0 ? flow_friction_deg : repose_deg * kFlowShare);
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
    grid.relax_active(0.001);
  }
  for (int n = 0; n < max_relax_steps && grid.active_count() > 0; ++n, ++steps)
    grid.relax_active(0.001);
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
      world.grid(grid).relax_active(0.001);
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

/// A granular column collapse (Lube et al. 2004, axisymmetric): a cylinder of radius r and height a r
/// released on a floor, run to rest. The deposit's runout R is where the azimuthal mean height falls below 1
/// % of the column's height (the thin edge a camera sees as the front).
struct ColumnCollapse {
  double time_to_rest_s = 0.0;
  double runout_m = 0.0;   // R: the deposit's radius
  double volume_m3 = 0.0;  // before, and after
  double volume_after_m3 = 0.0;
  bool at_rest = false;
  int cells = 0;
  long cell_updates = 0;
};

inline ColumnCollapse collapse_column(double radius_m, double aspect, double cell_m, double max_time_s = 60.0,
                                      double repose_deg = 34.0, double runout_factor = 6.0) {
  ColumnCollapse out;
  const double height = aspect * radius_m;
  // room for the laboratory runout plus a margin
  const double room = radius_m * (1.0 + runout_factor);
  out.cells = 2 * static_cast<int>(std::ceil(room / cell_m)) + 1;
  bulk::HeightGrid grid({out.cells, out.cells, cell_m}, test_material(repose_deg), {});
  const double c = 0.5 * out.cells * cell_m;
  for (int j = 0; j < out.cells; ++j)
    for (int i = 0; i < out.cells; ++i)
      if (std::hypot((i + 0.5) * cell_m - c, (j + 0.5) * cell_m - c) < radius_m)
        grid.add_volume(i, j, height * grid.cell_area_m2());
  out.volume_m3 = grid.total_volume_m3();
  const double dt = 0.001;
  long steps = 0;
  while (grid.active_count() > 0 && static_cast<double>(steps) * dt < max_time_s) {
    grid.relax_active(dt);
    out.cell_updates += static_cast<long>(grid.examined_count()) * grid.substeps();
    ++steps;
  }
  out.at_rest = grid.active_count() == 0;
  out.time_to_rest_s = static_cast<double>(steps) * dt;
  out.volume_after_m3 = grid.total_volume_m3();
  // azimuthal mean height by ring, one cell wide
  const int rings = out.cells / 2 + 1;
  std::vector<double> sum(static_cast<std::size_t>(rings), 0.0), count(static_cast<std::size_t>(rings), 0.0);
  for (int j = 0; j < out.cells; ++j)
    for (int i = 0; i < out.cells; ++i) {
      const auto ring =
          static_cast<std::size_t>(std::hypot((i + 0.5) * cell_m - c, (j + 0.5) * cell_m - c) / cell_m);
      if (ring >= sum.size()) continue;
      sum[ring] += grid.height(i, j);
      count[ring] += 1.0;
    }
  for (std::size_t ring = 0; ring < sum.size(); ++ring)
    if (count[ring] > 0.0 && sum[ring] / count[ring] >= 0.01 * height)
      out.runout_m = (static_cast<double>(ring) + 1.0) * cell_m;
  return out;
}

}  // namespace harbour::scenes
