// The wheeled machines' exercises (the RTG's on its tyres too) under their autopilots, at the simulation's
// fixed step.
#include <benchmark/benchmark.h>

#include <memory>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"

namespace harbour {
namespace {

// An exercise end to end: ODE, the tyres' force elements, the coupling or the boom, the autopilot and the
// evaluation; from the start again when it ends.
void BM_VehicleExercise(benchmark::State& state, const char* name) {
  const sim::ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR "/exercises/") + name + ".yaml");
  auto sim = std::make_unique<sim::Simulation>(exercise.scenario);
  auto pilot = sim::make_pilot(exercise);
  auto evaluator = std::make_unique<sim::Evaluator>(exercise);
  for (auto _ : state) {
    if (evaluator->finished() || sim->time_s() >= exercise.rules.time_limit_s) {
      state.PauseTiming();
      sim = std::make_unique<sim::Simulation>(exercise.scenario);
      pilot = sim::make_pilot(exercise);
      evaluator = std::make_unique<sim::Evaluator>(exercise);
      state.ResumeTiming();
    }
    const scene::Controls in = pilot->next(*sim);
    sim->step(in);
    evaluator->observe(*sim, in);
  }
  if (sim->diverged()) state.SkipWithError(sim->divergence().c_str());
  state.counters["real_time_factor"] =
      benchmark::Counter(sim::Simulation::kStep_s, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK_CAPTURE(BM_VehicleExercise, tractor_mafi_park, "tractor_mafi_park")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(5.0);
BENCHMARK_CAPTURE(BM_VehicleExercise, tractor_ramp_mafi, "tractor_ramp_mafi")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(5.0);
BENCHMARK_CAPTURE(BM_VehicleExercise, reach_stacker_stack, "reach_stacker_stack")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(5.0);
BENCHMARK_CAPTURE(BM_VehicleExercise, rtg_truck_to_block, "rtg_truck_to_block")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(5.0);
BENCHMARK_CAPTURE(BM_VehicleExercise, rtg_rehandle, "rtg_rehandle")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(5.0);
BENCHMARK_CAPTURE(BM_VehicleExercise, reach_stacker_truck_slalom, "reach_stacker_truck_slalom")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(5.0);
BENCHMARK_CAPTURE(BM_VehicleExercise, tractor_semi_reverse, "tractor_semi_reverse")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(5.0);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
