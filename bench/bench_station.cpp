// The station's real-time loop: what it adds to each simulation step (input sampling through SDL and the
// mapping, the command queue, the hand-off to the record keeper, snapshots), and how long a device change
// takes to reach the step that uses it. Results: docs/benchmarks.md.

#include <benchmark/benchmark.h>

#include <SDL.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>
#include <vector>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/ig/RenderThread.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"
#include "harbour/station/DeviceInput.h"
#include "harbour/station/DeviceMappingFile.h"
#include "harbour/station/RealTimeLoop.h"
#include "harbour/station/Session.h"
#include "scenes/StationScenes.h"
#include "scenes/StsScenes.h"

namespace harbour {
namespace {

using Clock = std::chrono::steady_clock;

// two T.16000M-like sticks, bound through the shipped desk mapping
struct Sticks {
  std::vector<SDL_Joystick*> sticks;
  Sticks() {
    station::init_sdl_joysticks();
    for (int n = 0; n < 2; ++n)
      sticks.push_back(SDL_JoystickOpen(scenes::attach_flight_stick()));
  }
  ~Sticks() {
    for (SDL_Joystick* j : sticks)
      SDL_JoystickClose(j);
    while (SDL_NumJoysticks() > 0)
      SDL_JoystickDetachVirtual(0);
    station::quit_sdl_joysticks();
  }
};

std::unique_ptr<station::DeviceInput> desk_input(const scene::ControlTable& table) {
  auto input = std::make_unique<station::DeviceInput>(
      table, station::load_device_mapping(HARBOUR_DATA_DIR "/devices/sts_dual_joystick.yaml", table));
  input->maintain();
  return input;
}

// The simulation alone: the autopilot's controls and one step (what the loop wraps).
void BM_SimulationStep(benchmark::State& state) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  auto sim = std::make_unique<sim::Simulation>(exercise.scenario);
  auto pilot = std::make_unique<sim::GantryAutopilot>(exercise);
  for (auto _ : state) {
    if (sim->steps() >= 60000) {
      state.PauseTiming();
      sim = std::make_unique<sim::Simulation>(exercise.scenario);
      pilot = std::make_unique<sim::GantryAutopilot>(exercise);
      state.ResumeTiming();
    }
    sim->single_step(pilot->next(*sim));
  }
}
BENCHMARK(BM_SimulationStep)->Unit(benchmark::kMicrosecond)->MinTime(3.0);

// The same steps through the loop's tick: plus command queue, hand-off, snapshots to three readers every
// fourth step, and the controls sampled from two SDL sticks (the autopilot still decides; the sample is
// taken and discarded so the station's input cost is in the tick). evaluated:1 adds what a session adds on
// the step thread: the evaluation of each step, its progress looked at, its figures copied every 50 steps.
void BM_LoopTick(benchmark::State& state) {
  const bool evaluated = state.range(0) != 0;
  const Sticks sticks;
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  auto sim = std::make_unique<sim::Simulation>(exercise.scenario);
  auto pilot = std::make_unique<sim::GantryAutopilot>(exercise);
  auto input = desk_input(sim->control_table());
  auto loop = std::make_unique<station::RealTimeLoop>(*sim);
  auto evaluator = std::make_unique<sim::Evaluator>(exercise);
  sim::Progress handed;
  sim::Metrics published;
  sim::reserve_lists(published);
  const auto wire = [&] {
    loop->set_pilot([&](const sim::Simulation& s) {
      benchmark::DoNotOptimize(input->sample());
      return pilot->next(s);
    });
    if (evaluated)
      loop->set_observer([&](const sim::Simulation& s, const scene::Controls& in) {
        evaluator->observe(s, in);
        const sim::Progress now = sim::progress(evaluator->metrics());
        if (now.grew_since(handed) || s.steps() % 50 == 0) {
          handed = now;
          published = evaluator->metrics();
        }
      });
  };
  wire();
  station::StepRecord drained;
  for (auto _ : state) {
    if (sim->steps() % 1000 == 0) {  // the record keeper's side, off the clock
      state.PauseTiming();
      while (loop->records().pop(drained)) {
      }
      if (sim->steps() >= 60000) {
        loop.reset();
        sim = std::make_unique<sim::Simulation>(exercise.scenario);
        pilot = std::make_unique<sim::GantryAutopilot>(exercise);
        loop = std::make_unique<station::RealTimeLoop>(*sim);
        evaluator = std::make_unique<sim::Evaluator>(exercise);
        wire();
      }
      state.ResumeTiming();
    }
    loop->run_ticks(1);
  }
}
BENCHMARK(BM_LoopTick)->Arg(0)->Arg(1)->ArgNames({"evaluated"})->Unit(benchmark::kMicrosecond)->MinTime(3.0);

// The bulk material's hand-off to a reader (every 50th tick in a bulk exercise, to the image generator and
// the console): mhc_coal_discharge after 20 s of the grab's work. Unchanged: the tile versions compared,
// nothing copied (most hand-offs); whole: every tile copied (a buffer's first fill).
void BM_BulkHandOff(benchmark::State& state) {
  const sim::ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/mhc_coal_discharge.yaml");
  sim::Simulation simulation(exercise.scenario);
  const std::unique_ptr<sim::Pilot> pilot = sim::make_pilot(exercise);
  while (simulation.time_s() < 20.0)
    simulation.step(pilot->next(simulation));
  const bool whole = state.range(0) == 1;
  scene::BulkView view;
  bulk::publish(*simulation.bulk(), view);
  for (auto _ : state) {
    if (whole) view.grids.clear();
    benchmark::DoNotOptimize(bulk::publish(*simulation.bulk(), view));
  }
  std::size_t cells = 0;
  for (const scene::BulkView::Grid& g : view.grids)
    cells += static_cast<std::size_t>(g.cells_x * g.cells_y);
  state.counters["cells"] = static_cast<double>(cells);
}
BENCHMARK(BM_BulkHandOff)->Arg(0)->Arg(1)->ArgNames({"whole"})->Unit(benchmark::kMicrosecond)->MinTime(2.0);

// The pieces on their own.
void BM_SampleTwoSticks(benchmark::State& state) {
  const Sticks sticks;
  const scene::ControlTable table = scenes::sts_controls();
  auto input = desk_input(table);
  for (auto _ : state)
    benchmark::DoNotOptimize(input->sample());
}
BENCHMARK(BM_SampleTwoSticks)->Unit(benchmark::kMicrosecond);

void BM_WriteSnapshot(benchmark::State& state) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  const sim::Simulation sim(exercise.scenario);
  auto snapshot = std::make_unique<scene::Snapshot>();
  for (auto _ : state) {
    sim.write_snapshot(*snapshot);
    benchmark::DoNotOptimize(snapshot->entity_count);
  }
}
BENCHMARK(BM_WriteSnapshot)->Unit(benchmark::kMicrosecond);

// A device change to the step that steps with it: the loop paced at 1 kHz samples the sticks right before
// each step; the hoist stick moves at a random moment and the time to the first step whose controls hold
// it is the iteration time.
void BM_DeviceToStepLatency(benchmark::State& state) {
  const Sticks sticks;
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  sim::Simulation sim(exercise.scenario);
  auto input = desk_input(sim.control_table());
  const auto hoist = static_cast<std::size_t>(sim.control_table().find("hoist"));
  station::RealTimeLoop loop(sim);
  std::atomic<double> wanted{0.0};
  std::atomic<Clock::rep> seen_at{0};
  loop.set_sampler([&] {
    const scene::Controls c = input->sample();
    if (seen_at.load() == 0 && c.value[hoist] != 0.0 && (c.value[hoist] > 0.0) == (wanted.load() > 0.0))
      seen_at = Clock::now().time_since_epoch().count();
    return c;
  });
  std::thread drain([&] {
    station::StepRecord r;
    while (loop.running() || !loop.records().empty())
      if (!loop.records().pop(r)) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  loop.start();
  std::vector<double> latencies;
  std::uint64_t seed = 12345;
  Sint16 value = 20000;
  for (auto _ : state) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    std::this_thread::sleep_for(std::chrono::microseconds(2000 + (seed >> 33) % 3000));  // a random moment
    value = static_cast<Sint16>(-value);
    wanted = value;
    seen_at = 0;
    const Clock::time_point moved = Clock::now();
    SDL_JoystickSetVirtualAxis(sticks.sticks[1], 1, value);
    while (seen_at.load() == 0)
      std::this_thread::yield();
    const double latency =
        std::chrono::duration<double>(Clock::duration(seen_at.load()) - moved.time_since_epoch()).count();
    latencies.push_back(latency);
    state.SetIterationTime(latency);
  }
  loop.stop();
  drain.join();
  std::sort(latencies.begin(), latencies.end());
  state.counters["median_ms"] = latencies[latencies.size() / 2] * 1e3;
  state.counters["p99_ms"] = latencies[latencies.size() * 99 / 100] * 1e3;
  state.counters["max_ms"] = latencies.back() * 1e3;
}
BENCHMARK(BM_DeviceToStepLatency)->UseManualTime()->Unit(benchmark::kMicrosecond)->Iterations(1000);

// A live session keeping real time on this machine: the autopilot drives sts_discharge at 1 kHz paced to
// the wall clock, the keeper records and evaluates off the step thread; with `drawing` the image generator
// draws the cab view at 1280x720 as fast as it can beside it. One iteration is the whole run (60 s alone,
// 20 s drawing); the counters are the loop's own figures.
void BM_LiveRun(benchmark::State& state) {
  const bool drawing = state.range(0) != 0;
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  station::SessionOptions options;
  options.trainee = "t1";
  options.database = scenes::fresh_database("harbour_bench_live.db");
  options.record = scenes::temp_path("harbour_bench_live.hsrc");
  for (auto _ : state) {
    station::Session session(exercise, options);
    sim::GantryAutopilot pilot(exercise);
    session.loop().set_pilot([&](const sim::Simulation& s) { return pilot.next(s); });
    std::unique_ptr<ig::RenderThread> render;
    if (drawing)
      render = std::make_unique<ig::RenderThread>(
          session.simulation().scene(), ig::load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds()), 1280,
          720, std::vector<ig::View>{ig::View{}},
          [&] { return session.loop().latest_snapshot(station::kImageGeneratorReader); });
    session.start();
    std::this_thread::sleep_for(std::chrono::seconds(drawing ? 20 : 60));
    if (render) {
      state.counters["fps"] = render->fps();
      render->stop();
    }
    const station::SessionResult result = session.finish(station::SessionEnd::kInterrupted);
    const station::LoopStats& s = result.loop;
    state.counters["ticks"] = static_cast<double>(s.ticks);
    state.counters["late_ticks"] = static_cast<double>(s.late_ticks);
    state.counters["given_up"] = static_cast<double>(s.skipped_ticks);
    state.counters["longest_tick_us"] = s.longest_tick_s * 1e6;
    state.counters["mean_tick_us"] = s.mean_tick_s * 1e6;
    state.counters["real_time_factor"] = s.real_time_factor;
  }
  std::filesystem::remove(options.record);
}
BENCHMARK(BM_LiveRun)
    ->Arg(0)
    ->Arg(1)
    ->ArgNames({"drawing"})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
