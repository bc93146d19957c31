// A team session's costs: what drawing the other members' machines adds to a station's tick, and how old a
// member's published state is when another station's process has it (two processes on loopback DDS).
#include <benchmark/benchmark.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "harbour/machines/GantryAutopilot.h"
#include "harbour/net/DdsLink.h"
#include "harbour/station/RealTimeLoop.h"
#include "harbour/station/TeamPresence.h"
#include "scenes/StsScenes.h"

namespace harbour {
namespace {

// `count` members with three bodies each (a tractor and its trailer and load, say), moving
std::unique_ptr<station::TeamPresence> team_of(int count, const scene::SceneDescription& own) {
  std::vector<station::TeamMember> members;
  for (int m = 0; m < count; ++m) {
    station::TeamMember member;
    member.role = "tractor-" + std::to_string(m + 1);
    for (int b = 0; b < 3; ++b) {
      member.bodies.push_back({"body " + std::to_string(b), "tractor.chassis", {3, 1.2, 1.5}});
      member.start_poses.push_back({core::Mat3::identity(), {-10.0 * m, 5.0 * b, 1.5}});
    }
    members.push_back(member);
  }
  auto team = std::make_unique<station::TeamPresence>(own, members);
  for (int m = 0; m < count; ++m) {
    station::TeamSample sample;
    sample.role = "tractor-" + std::to_string(m + 1);
    for (std::uint16_t b = 0; b < 3; ++b) {
      sample.body.push_back(b);
      sample.motion.push_back(
          {{core::Mat3::rotation({0, 0, 1}, 0.3), {-10.0 * m, 5.0 * b, 1.5}}, {3, 0, 0}, {0, 0, 0.1}});
    }
    for (int k = 0; k < 2; ++k) {  // two samples: blending, as between any two
      sample.received_s = 1.0 + 0.02 * k;
      team->offer(sample);
    }
  }
  return team;
}

// One tick of the station's loop on `sts_discharge` under the autopilot, every snapshot reader on at its
// rate, alone and with one or three other members' machines (three bodies each) added to each snapshot and
// standing in the simulation as its obstacles.
void BM_LoopTickWithTeam(benchmark::State& state) {
  const int members = static_cast<int>(state.range(0));
  const bool team_on = members > 0;
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  auto sim = std::make_unique<sim::Simulation>(exercise.scenario);
  auto pilot = std::make_unique<sim::GantryAutopilot>(exercise);
  auto loop = std::make_unique<station::RealTimeLoop>(*sim);
  const auto team = team_of(members, sim->scene());
  const auto wire = [&] {
    loop->set_pilot([&](const sim::Simulation& s) { return pilot->next(s); });
    // the nine bodies as the simulation's obstacles too, standing on the quay beside the crane
    for (int k = 0; k < 3 * members; ++k) {
      sim::TeamInput obstacle;
      obstacle.kind = sim::TeamInput::Kind::kObstacleAt;
      obstacle.slot = k;
      obstacle.pose.position = {-10.0 * (k / 3), 60.0 + 8.0 * (k % 3),
                                1.5};  // on the quay, clear of the crane
      obstacle.half_extents_m = {3, 1.2, 1.5};
      sim->team_input(obstacle);
    }
    if (team_on)
      loop->set_addition([&](scene::Snapshot& s) { team->write(s, 1.05); },
                         1u << station::kImageGeneratorReader | 1u << station::kConsoleReader |
                             1u << station::kPictureReader);
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
        wire();
      }
      state.ResumeTiming();
    }
    loop->run_ticks(1);
  }
}
BENCHMARK(BM_LoopTickWithTeam)->Arg(0)->Arg(1)->Arg(3)->ArgNames({"members"})->Unit(benchmark::kMicrosecond);

// A member's state from another process at 50 Hz, as a station's team thread takes it: its age on arrival
// (the sender's and the receiver's monotonic clocks are the host's one clock) over 20 s.
void BM_TeamStateAge(benchmark::State& state) {
  constexpr int kDomain = 199;
  for (auto _ : state) {
    const pid_t child = fork();  // before either process has a DDS participant
    if (child == 0) {
      net::TeamLink crane("bench-crane", "bench-team", "crane", kDomain);
      net::TeamState s;
      s.entity_index(std::vector<std::uint16_t>{0, 1, 2});
      s.motion(std::vector<float>(39, 1.0f));
      auto next = std::chrono::steady_clock::now();
      for (int k = 0; k < 50 * 24; ++k) {
        next += std::chrono::milliseconds(20);
        std::this_thread::sleep_until(next);
        s.step(k);
        crane.publish(s);
      }
      _exit(0);
    }
    net::TeamLink tractor("bench-tractor", "bench-team", "tractor", kDomain);
    std::vector<double> ages_ms;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(22);
    while (std::chrono::steady_clock::now() < until) {
      if (!tractor.wait(std::chrono::milliseconds(50))) continue;
      const std::int64_t now = net::TeamLink::monotonic_ns();
      for (const net::TeamState& t : tractor.take())
        ages_ms.push_back(static_cast<double>(now - t.sent_ns()) * 1e-6);
    }
    waitpid(child, nullptr, 0);
    std::sort(ages_ms.begin(), ages_ms.end());
    if (ages_ms.empty()) {
      state.SkipWithError("no state arrived");
      return;
    }
    const auto at = [&](double q) {
      return ages_ms[static_cast<std::size_t>(q * static_cast<double>(ages_ms.size() - 1))];
    };
    state.counters["states"] = static_cast<double>(ages_ms.size());
    state.counters["age_p50_ms"] = at(0.5);
    state.counters["age_p99_ms"] = at(0.99);
    state.counters["age_max_ms"] = ages_ms.back();
  }
}
BENCHMARK(BM_TeamStateAge)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

}  // namespace
}  // namespace harbour

BENCHMARK_MAIN();
