// The STS discharge exercise, headless: physics (ODE) + hoist ropes (cable model) + twistlocks + evaluation,
// driven by the autopilot. Real-time factor = simulated time / compute time. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include "harbour/sim/Autopilot.h"
#include "scenes/StsScenes.h"

namespace harbour {
namespace {

void BM_StsExerciseStep(benchmark::State& state) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  auto sim = std::make_unique<sim::Simulation>(exercise.scenario);
  auto pilot = std::make_unique<sim::Autopilot>(exercise);
  auto evaluator = std::make_unique<sim::Evaluator>(exercise);
  for (auto _ : state) {
    if (pilot->done()) {  // start the exercise again
      state.PauseTiming();
      sim = std::make_unique<sim::Simulation>(exercise.scenario);
      pilot = std::make_unique<sim::Autopilot>(exercise);
      evaluator = std::make_unique<sim::Evaluator>(exercise);
      state.ResumeTiming();
    }
    const sim::Inputs in = pilot->next(*sim);
    sim->step(in);
    evaluator->observe(*sim, in);
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(sim::Simulation::kStep_s, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_StsExerciseStep)->Unit(benchmark::kMicrosecond)->MinTime(5.0);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
