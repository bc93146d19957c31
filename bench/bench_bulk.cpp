// Bulk-material benchmarks: the paper's active-cell list against the full sweep (its baseline).
// Results and the command that produced them: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <cmath>

#include "scenes/BulkScenes.h"

namespace harbour {
namespace {

// one 1 kHz step of a grab digging and dumping on an n x n yard grid (grab + parcels + flow); the 8 s cycle
// digs for 6 s and dumps for 2 s: timed over the digging (steps 2000-6000) or over a whole cycle, whose dump
// (12 m^3 from 2 m) flows for a few seconds
void dig(benchmark::State& state, bool full_sweep) {
  // warm up into the bite with the active list, which is bit-identical to the sweep and much faster
  scenes::DigScene scene(static_cast<int>(state.range(0)));
  for (int n = 0; n < 2000; ++n)
    scene.step();
  scene.world.use_full_sweep(full_sweep);
  double examined = 0;
  for (auto _ : state) {
    scene.step();
    examined += static_cast<double>(scene.world.grid(scene.grid).examined_count());
  }
  state.counters["cells_per_step"] = benchmark::Counter(examined, benchmark::Counter::kAvgIterations);
  state.counters["cell_updates_per_s"] = benchmark::Counter(examined, benchmark::Counter::kIsRate);
}

void BM_DigActiveList(benchmark::State& state) {
  dig(state, false);
}
void BM_DigFullSweep(benchmark::State& state) {
  dig(state, true);
}
void BM_DigAndDumpCycle(benchmark::State& state) {
  dig(state, false);
}
BENCHMARK(BM_DigActiveList)
    ->Arg(256)
    ->Arg(512)
    ->Arg(1024)
    ->Arg(2048)
    ->Iterations(4000)  // the digging: steps 2000-6000 of the cycle
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DigFullSweep)->Arg(256)->Arg(512)->Arg(1024)->Arg(2048)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DigAndDumpCycle)
    ->Arg(256)
    ->Arg(2048)
    ->Iterations(8000)  // a whole cycle from step 2000: digging, the dump and its flow
    ->Unit(benchmark::kMicrosecond);

// a steady pour onto the top of a relaxed heap of diameter D [m]: the avalanche front grows with D.
// The grid is sized to the heap (1.25 D), as a sweep-based simulator would size it.
void pour(benchmark::State& state, bool full_sweep) {
  const double diameter_m = static_cast<double>(state.range(0));
  const int cells = static_cast<int>(std::ceil(1.25 * diameter_m / 0.1));
  const bulk::Material m = scenes::test_material(35.0);
  bulk::HeightGrid grid({cells, cells, 0.1}, m, {});
  const double radius = 0.5 * diameter_m, t = std::tan(m.angle_of_repose_rad), c = 0.05 * cells;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const double r = std::hypot((i + 0.5) * 0.1 - c, (j + 0.5) * 0.1 - c);
      if (r < radius) grid.add_volume(i, j, (radius - r) * t * grid.cell_area_m2());
    }
  for (int n = 0; n < 200000 && grid.active_count() > 0; ++n)
    grid.relax_active(0.001);
  const int top = cells / 2;
  for (int n = 0; n < 3000; ++n) {  // reach a steady avalanche regime
    grid.add_volume(top, top, 0.002);
    grid.relax_active(0.001);
  }
  double examined = 0;
  for (auto _ : state) {
    grid.add_volume(top, top, 0.002);  // 2 m^3/s at 1 kHz
    if (full_sweep)
      grid.relax_full_sweep(0.001);
    else
      grid.relax_active(0.001);
    examined += static_cast<double>(grid.examined_count());
  }
  state.counters["cells_per_step"] = benchmark::Counter(examined, benchmark::Counter::kAvgIterations);
}

void BM_PourActiveList(benchmark::State& state) {
  pour(state, false);
}
void BM_PourFullSweep(benchmark::State& state) {
  pour(state, true);
}
BENCHMARK(BM_PourActiveList)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PourFullSweep)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMicrosecond);

// A granular column (aspect a = 2) collapsing on a floor to rest, radius r at cell size dx (issue 15's
// targets): simulated time to rest against sqrt(H/g), runout against Lube et al. (2004), wall time.
void BM_ColumnCollapse(benchmark::State& state) {
  const double radius = static_cast<double>(state.range(0)) / 10.0,
               cell = static_cast<double>(state.range(1)) / 1000.0;
  scenes::ColumnCollapse c;
  for (auto _ : state)
    c = scenes::collapse_column(radius, 2.0, cell, 60.0, 34.0, 3.0);
  state.counters["rest_s"] = c.time_to_rest_s;
  state.counters["rest_over_sqrt_H_g"] = c.time_to_rest_s / std::sqrt(2.0 * radius / 9.81);
  state.counters["runout"] = (c.runout_m - radius) / radius;
  state.counters["cells"] = c.cells;
  state.counters["updates"] = static_cast<double>(c.cell_updates);
}
BENCHMARK(BM_ColumnCollapse)
    ->Args({16, 50})
    ->Args({32, 50})
    ->Args({64, 50})
    ->Args({16, 25})
    ->Args({16, 100})
    ->ArgNames({"r_dm", "cell_mm"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
