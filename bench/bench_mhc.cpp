// The mobile harbour crane, headless: physics (ODE: house, boom, grab on hinges and a slider) + the luffing
// and hoist ropes (cable model, wave segments) + limiter and pads, under a scripted operator working every
// lever. Real-time factor = simulated time / compute time. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <cmath>

#include "scenes/MhcScenes.h"

namespace harbour {
namespace {

// slewing to and fro, luffing in and out, hoisting and working the grab, each on its own period
sim::Controls scripted_operator(const sim::Simulation& sim) {
  const sim::ControlTable& table = sim.control_table();
  sim::Controls c = table.neutral();
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

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
