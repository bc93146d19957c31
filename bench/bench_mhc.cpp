// The mobile harbour crane, headless: physics (ODE: house, boom, grab on hinges and a slider) + the luffing
// and hoist ropes (cable model, wave segments) + limiter and pads, under a scripted operator working every
// lever. Real-time factor = simulated time / compute time. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"
#include "scenes/MhcScenes.h"

namespace harbour {
namespace {

// slewing to and fro, luffing in and out, hoisting and working the grab, each on its own period
scene::Controls scripted_operator(const sim::Simulation& sim) {
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = table.neutral();
  const double t = sim.time_s();
  const auto set = [&](const char* label, double value) {
    c.value[static_cast<std::size_t>(table.find(label))] = value;
  };
  set("slew", std::sin(t / 10.0));
  set("luff", 0.5 * std::sin(t / 7.0));
  set("hoist", 0.5 * std::sin(t / 5.0));
  set("grab", std::sin(t / 4.0) > 0.0 ? 1.0 : -1.0);
  return c;
}

void BM_MhcStep(benchmark::State& state) {
  const sim::ScenarioSettings scenario = scenes::mhc_on_quay(HARBOUR_DATA_DIR);
  auto sim = std::make_unique<sim::Simulation>(scenario);
  for (auto _ : state) {
    if (sim->time_s() >= 120.0) {  // start again
      state.PauseTiming();
      sim = std::make_unique<sim::Simulation>(scenario);
      state.ResumeTiming();
    }
    sim->step(scripted_operator(*sim));
  }
  if (sim->diverged()) state.SkipWithError(sim->divergence().c_str());
  state.counters["real_time_factor"] =
      benchmark::Counter(sim::Simulation::kStep_s, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_MhcStep)->Unit(benchmark::kMicrosecond)->MinTime(5.0);

// The coal discharge on a 1024^2 bulk area at 10 or 5 cm cells (bench/data/mhc_discharge_1024_*.yaml) under
// the grab autopilot: ODE, the boom and grab ropes' wave segments, the grab's contact and bite, the hold
// riding on the vessel, the hopper's outflow, the material flowing, the evaluation; the first 120 s of the
// exercise (a bite dug, hoisted, slewed and dropped into the hopper), then again.
void BM_MhcDischarge1024(benchmark::State& state, const char* file) {
  const sim::ExerciseSettings exercise = io::load_exercise(std::string(HARBOUR_BENCH_DATA_DIR "/") + file);
  auto sim = std::make_unique<sim::Simulation>(exercise.scenario);
  auto pilot = sim::make_pilot(exercise);
  auto evaluator = std::make_unique<sim::Evaluator>(exercise);
  for (auto _ : state) {
    if (sim->time_s() >= 120.0) {
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
  long cells = 0;
  for (int g = 0; g < sim->bulk()->grid_count(); ++g)
    cells += static_cast<long>(sim->bulk()->grid(g).cells_x()) * sim->bulk()->grid(g).cells_y();
  state.counters["bulk_cells"] = static_cast<double>(cells);
}
BENCHMARK_CAPTURE(BM_MhcDischarge1024, cells_10cm, "mhc_discharge_1024_10cm.yaml")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(10.0);
BENCHMARK_CAPTURE(BM_MhcDischarge1024, cells_5cm, "mhc_discharge_1024_5cm.yaml")
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(10.0);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
