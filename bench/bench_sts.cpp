// The STS discharge exercises, headless: physics (ODE) + hoist ropes (cable model) + twistlocks + evaluation,
// driven by the autopilot. Real-time factor = simulated time / compute time. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include "harbour/machines/GantryAutopilot.h"
#include "scenes/StsScenes.h"

namespace harbour {
namespace {

void run_exercise(benchmark::State& state, const sim::ExerciseSettings& exercise) {
  auto sim = std::make_unique<sim::Simulation>(exercise.scenario);
  auto pilot = std::make_unique<sim::GantryAutopilot>(exercise);
  auto evaluator = std::make_unique<sim::Evaluator>(exercise);
  for (auto _ : state) {
    if (pilot->done()) {  // start the exercise again
      state.PauseTiming();
      sim = std::make_unique<sim::Simulation>(exercise.scenario);
      pilot = std::make_unique<sim::GantryAutopilot>(exercise);
      evaluator = std::make_unique<sim::Evaluator>(exercise);
      state.ResumeTiming();
    }
    const scene::Controls in = pilot->next(*sim);
    sim->step(in);
    evaluator->observe(*sim, in);
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(sim::Simulation::kStep_s, benchmark::Counter::kIsIterationInvariantRate);
}
void BM_StsExerciseStep(benchmark::State& state) {
  run_exercise(state, scenes::sts_discharge_exercise(HARBOUR_DATA_DIR));
}
BENCHMARK(BM_StsExerciseStep)->Unit(benchmark::kMicrosecond)->MinTime(5.0);

// The hold exercise: more boxes, four trucks, a hatch cover carried, boxes hoisted through the cell guides.
void BM_StsHoldExerciseStep(benchmark::State& state) {
  run_exercise(state, io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_bay12_hold.yaml"));
}
BENCHMARK(BM_StsHoldExerciseStep)->Unit(benchmark::kMicrosecond)->MinTime(5.0);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
