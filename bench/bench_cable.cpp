// Cable-and-pulley benchmarks: one 1 kHz step of the shipped STS hoist and MHC grab reevings while hoisting,
// with the wave model on and as pure springs. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <cmath>

#include "scenes/HoistScenes.h"

namespace harbour {
namespace {

using Build = void (*)(scenes::HoistScene&, const std::string&, int);

void run(benchmark::State& state, Build build, int max_substeps) {
  scenes::HoistScene scene;
  build(scene, HARBOUR_DATA_DIR, max_substeps);
  for (int k = 0; k < 2000; ++k)
    scene.step();  // settle
  for (auto& c : scene.commands)
    c.lever = -0.5;  // hoist at half speed (and close, on the grab)
  long steps = 0;
  for (auto _ : state) {
    scene.hoist->step(0.001, scene.commands, scene.bodies);
    scene.bodies.step(0.001, scene.gravity);
    if (++steps % 4000 == 0)
      for (auto& c : scene.commands)
        c.lever = -c.lever;  // up and down, staying within the rope on the drums
  }
  for (const auto& b : scene.bodies.bodies)
    if (!std::isfinite(b.position.z)) state.SkipWithError("the scene went non-finite");
  int springs = 0;
  for (int r = 0; r < scene.hoist->rope_count(); ++r)
    for (int g = 0; g < scene.hoist->segment_count(r); ++g)
      springs += !scene.hoist->oscillating(r, g);
  state.counters["spring_segments"] = springs;
  state.counters["wave_nodes"] = scene.nodes;
  state.counters["ns_per_node"] =
      benchmark::Counter(static_cast<double>(scene.nodes),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_StsHoistWave(benchmark::State& s) {
  run(s, &scenes::build_sts, 8);
}
void BM_StsHoistSpring(benchmark::State& s) {
  run(s, &scenes::build_sts, 0);
}
void BM_MhcGrabWave(benchmark::State& s) {
  run(s, &scenes::build_mhc, 8);
}
void BM_MhcGrabSpring(benchmark::State& s) {
  run(s, &scenes::build_mhc, 0);
}
BENCHMARK(BM_StsHoistWave)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StsHoistSpring)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MhcGrabWave)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MhcGrabSpring)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
