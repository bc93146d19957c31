// Steady-state stepping allocates nothing: this binary replaces the global operator new and ODE's allocator
// with counting ones, runs a whole exercise under the autopilot and counts what each step allocated.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include <ode/ode.h>

#include "harbour/bulk/BulkWorld.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/scene/HandSignals.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"
#include "harbour/sim/Recording.h"
#include "harbour/sim/Simulation.h"
#include "harbour/station/RealTimeLoop.h"

// the replacements below pair malloc with free on purpose
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}

namespace harbour::sim {
namespace {

void* ode_alloc(dsizeint size) {
  ++g_allocations;
  return std::malloc(size);
}
void* ode_realloc(void* p, dsizeint, dsizeint size) {
  ++g_allocations;
  return std::realloc(p, size);
}
void ode_free(void* p, dsizeint) {
  std::free(p);
}

struct Count {
  long steps = 0;       // after the warm-up
  long allocating = 0;  // steps that allocated, other than ...
  long attaching = 0;   // ... those that fixed a load on the spreader or a truck (ODE allocates the joint)
};

// Steps `exercise` under the autopilot and counts the steps after `warm_up_s` that allocated.
Count count_allocations(const std::string& exercise_name, double warm_up_s, double run_s) {
  dSetAllocHandler(ode_alloc);
  dSetReallocHandler(ode_realloc);
  dSetFreeHandler(ode_free);
  const ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/" + exercise_name + ".yaml");
  Simulation simulation(exercise.scenario);
  GantryAutopilot pilot(exercise);
  Count count;
  while (simulation.time_s() < run_s) {
    const scene::Controls controls = pilot.next(simulation);  // the station's side: decided outside the step
    const int attachments = simulation.world().attachments_made();
    const long before = g_allocations.load();
    simulation.step(controls);
    const bool allocated = g_allocations.load() != before;
    if (simulation.time_s() <= warm_up_s) continue;
    ++count.steps;
    if (simulation.world().attachments_made() != attachments)
      ++count.attaching;
    else if (allocated)
      ++count.allocating;
  }
  return count;
}

TEST(Allocation, AHoldDischargeStepsWithoutAllocatingOnceWarm) {
  // sts_bay12_hold: deck boxes, a hatch cover and hold boxes through the cell guides; contacts come and go
  const Count count = count_allocations("sts_bay12_hold", 5.0, 200.0);
  EXPECT_GT(count.steps, 190000);
  EXPECT_GE(count.attaching, 3);  // boxes locked on and set down on trucks: contacts come and go
  EXPECT_EQ(count.allocating, 0) << count.allocating << " of " << count.steps << " steps allocated";
}

// A station's loop under the exercise's pilot, evaluated on the step thread as a station's session does
// (the evaluation after each step, its progress looked at, its figures copied out every 50 steps) and
// handing on a keyframe every ten seconds: warmed up 5 s, then `seconds` of ticks one at a time, counted when
// they allocate (other than by fixing a load on: ODE allocates the joint; and the keyframes, counted apart:
// a state saved allocates its bytes). The readers look after every second, as the image generator and the
// console would.
station::LoopSettings recorded_loop() {
  station::LoopSettings settings;
  settings.keyframe_every_steps = Recorder::kKeyframeEvery;
  return settings;
}

struct StationTicks {
  explicit StationTicks(const std::string& exercise_name)
      : exercise(io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/" + exercise_name + ".yaml")),
        simulation(exercise.scenario),
        pilot(make_pilot(exercise)),
        evaluator(exercise),
        loop(simulation, recorded_loop()) {
    loop.set_pilot([this](const Simulation& s) { return pilot->next(s); });
    reserve_lists(published);
    loop.set_observer([this](const Simulation& s, const scene::Controls& in) {
      evaluator.observe(s, in);
      const Progress now = progress(evaluator.metrics());
      if (now.grew_since(handed) || s.steps() % 50 == 0) {
        handed = now;
        published = evaluator.metrics();
        goals_met = evaluator.goals_met();
      }
    });
    loop.run_ticks(5000);
    drain();
  }
  void drain() {  // the record keeper's side (another thread in a station)
    while (loop.records().pop(record))
      if (record.kind == station::StepRecord::Kind::kKeyframe) loop.release_keyframe(record.keyframe_slot);
  }
  // `signalled`: a signaller's hoist or stop given at each second (the evaluator times the answers)
  long allocating_ticks(int seconds, bool signalled = false) {
    long allocating = 0;
    for (int second = 0; second < seconds; ++second) {
      if (signalled) {
        station::LoopCommand signal;
        signal.kind = station::LoopCommand::Kind::kInstructor;
        signal.instructor.kind = InstructorCommand::Kind::kSignal;
        signal.instructor.value = scene::find_hand_signal(second % 2 == 0 ? "hoist" : "stop");
        EXPECT_TRUE(loop.post(signal));
      }
      for (int k = 0; k < 1000; ++k) {
        const int attachments = simulation.world().attachments_made();
        const long before = g_allocations.load();
        loop.run_ticks(1);  // commands, controls, the step, its evaluation, the hand-off, snapshots
        if (simulation.steps() % Recorder::kKeyframeEvery == 0)
          ++keyframes;
        else if (g_allocations.load() != before && simulation.world().attachments_made() == attachments)
          ++allocating;
      }
      drain();
      loop.latest_snapshot(station::kImageGeneratorReader);
      loop.latest_bulk(station::kImageGeneratorReader);
      loop.latest_bulk(station::kConsoleReader);
    }
    return allocating;
  }
  ExerciseSettings exercise;
  Simulation simulation;
  std::unique_ptr<Pilot> pilot;
  Evaluator evaluator;
  Progress handed;
  Metrics published;
  bool goals_met = false;
  station::RealTimeLoop loop;
  station::StepRecord record;
  long keyframes = 0;
};

TEST(Allocation, TheStationsTickAndItsSnapshotsAllocateNothing) {
  StationTicks sts("sts_bay12_hold");
  const long allocating = sts.allocating_ticks(60, true);
  EXPECT_EQ(allocating, 0) << allocating << " of 60000 ticks allocated";
  EXPECT_EQ(sts.published.signals, 60);
  EXPECT_FALSE(sts.published.signal_delays_s.empty()) << "no signal was followed: nothing was timed";
  EXPECT_EQ(sts.keyframes, 6);
  EXPECT_GT(sts.published.time_s, 60.0) << "nothing was evaluated";
  // a snapshot is written into a reader's buffer without allocating, and the readers get the newest
  auto mine = std::make_unique<scene::Snapshot>();
  const long before = g_allocations.load();
  sts.simulation.write_snapshot(*mine);
  EXPECT_EQ(g_allocations.load(), before);
  const scene::Snapshot* s = sts.loop.latest_snapshot(station::kImageGeneratorReader);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->step, sts.simulation.steps());
}

// A bulk station: the grab digs, carries and drops coal (cells flow, the active list grows and shrinks), and
// each tick hands the changed tiles to the image generator's and the console's buffers.
TEST(Allocation, ABulkStationsTickAllocatesNothingOnceWarm) {
  StationTicks mhc("mhc_coal_discharge");
  const long allocating = mhc.allocating_ticks(90);
  EXPECT_GT(mhc.simulation.bulk()->unloaded_m3(), 5.0) << "the grab dropped no coal: nothing flowed";
  EXPECT_NE(mhc.loop.latest_bulk(station::kConsoleReader), nullptr);
  EXPECT_EQ(allocating, 0) << allocating << " of 90000 ticks allocated";
  EXPECT_GT(mhc.evaluator.metrics().handled_t, 5.0) << "nothing was evaluated";
}

}  // namespace
}  // namespace harbour::sim
