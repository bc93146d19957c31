// The image generator: frames per second of the STS deck exercise (ten boxes, the feeder, trucks, the crane
// and its ropes) drawn headless (EGL) from the cab and the chase view. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <osg/Image>

#include "harbour/ig/ImageGenerator.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Autopilot.h"

namespace harbour {
namespace {

void BM_Frame(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0)), height = static_cast<int>(state.range(1));
  const sim::ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_bay12_deck.yaml");
  sim::Simulation simulation(exercise.scenario);
  sim::Autopilot pilot(exercise);
  while (simulation.time_s() < 30.0)
    simulation.step(pilot.next(simulation));  // a box on the spreader
  ig::ImageGenerator generator(simulation.scene(), ig::load_visuals(HARBOUR_DATA_DIR "/visuals/harbour.yaml"),
                               width, height);
  ig::View view;
  view.kind = state.range(2) == 0 ? ig::View::Kind::kCab : ig::View::Kind::kChase;
  generator.set_view(view);
  auto snapshot = std::make_unique<sim::Snapshot>();
  for (auto _ : state) {
    for (int k = 0; k < 16; ++k)
      simulation.step(pilot.next(simulation));  // the scene moves between frames
    simulation.write_snapshot(*snapshot);
    generator.update(*snapshot);
    benchmark::DoNotOptimize(generator.render().data());
  }
  state.counters["fps"] = benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(generator.renderer());
}
BENCHMARK(BM_Frame)
    ->Args({1280, 720, 0})
    ->Args({1280, 720, 1})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->ArgNames({"w", "h", "chase"})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
