// The real-time loop's pacing, tested by its mechanism on a manual clock: each tick's work costs the time the
// test says, whatever the host's speed, so a busy machine cannot fail these and a fast one cannot pass them.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "harbour/io/RecordingFile.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/station/RealTimeLoop.h"
#include "harbour/station/Session.h"
#include "scenes/StationScenes.h"
#include "scenes/StsScenes.h"

namespace harbour::station {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

// Time moves only when the loop sleeps (to the time it asks for) or when a tick's work advances it.
class ManualClock final : public LoopClock {
 public:
  time_point now() override { return now_; }
  void sleep_until(time_point at) override {
    ++sleeps;
    now_ = std::max(now_, at);
  }
  void advance(microseconds work) { now_ += work; }
  double seconds() const { return std::chrono::duration<double>(now_.time_since_epoch()).count(); }
  std::int64_t sleeps = 0;

 private:
  time_point now_{};
};

// The loop run on the step thread until `steps` steps, each tick's work costing work(step) of clock time.
template <typename Work>
LoopStats run_paced(ManualClock& clock, std::int64_t steps, Work work, int ticks_per_wake = 1) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  sim::Simulation simulation(exercise.scenario);
  LoopSettings settings;
  settings.clock = &clock;
  settings.ticks_per_wake = ticks_per_wake;
  RealTimeLoop loop(simulation, settings);
  loop.set_pilot([&](const sim::Simulation& s) {
    clock.advance(work(s.steps()));
    return s.control_table().neutral();
  });
  loop.set_stop_when([&](const sim::Simulation& s) { return s.steps() >= steps; });
  loop.start();
  loop.join();
  return loop.stats();
}

TEST(LoopPacing, EveryTickThatFitsItsPeriodStartsOnTime) {
  ManualClock clock;
  const LoopStats s = run_paced(clock, 3000, [](std::int64_t) { return microseconds(300); });
  EXPECT_EQ(s.ticks, 3000);
  EXPECT_EQ(s.steps, 3000);
  EXPECT_EQ(s.late_ticks, 0);
  EXPECT_EQ(s.skipped_ticks, 0);
  EXPECT_TRUE(s.keeping_real_time);
  EXPECT_EQ(clock.sleeps, 2999);  // it waits out the rest of every period but the first
  EXPECT_NEAR(s.mean_tick_s, 300e-6, 1e-9);
  EXPECT_NEAR(clock.seconds(), 2.9993, 1e-9);  // the last tick starts at 2.999 s
  EXPECT_NEAR(s.real_time_factor, 3.0 / 2.9993, 1e-9);
}

// A tick that overruns by less than the catch-up bound (50 ms) is caught up: the ticks after it run back to
// back, late, until the loop is on time again; no simulated time is lost.
TEST(LoopPacing, AStallUnderTheCatchUpBoundIsCaughtUpTickByTick) {
  ManualClock clock;
  const LoopStats s = run_paced(
      clock, 3000, [](std::int64_t step) { return step == 1000 ? milliseconds(30) : microseconds(300); });
  EXPECT_EQ(s.skipped_ticks, 0);
  EXPECT_EQ(s.catch_up_limits, 0);
  EXPECT_TRUE(s.keeping_real_time);
  EXPECT_EQ(s.steps, 3000);
  EXPECT_EQ(s.ticks, 3000);
  // 29 ms behind after the stall, 0.7 ms made up by each tick: 41 ticks start a period or more late
  EXPECT_EQ(s.late_ticks, 41);
  EXPECT_NEAR(s.worst_lateness_s, 29e-3, 1e-9);
  EXPECT_NEAR(clock.seconds(), 2.9993, 1e-9);  // back on time by the end
}

// Behind by more than the bound, the loop gives the excess up instead of racing through it, counts what it
// gave up and reports that it no longer keeps real time; then it carries on at 1 kHz.
TEST(LoopPacing, FarBehindItGivesTheTimeUpAndSaysSo) {
  ManualClock clock;
  const LoopStats s = run_paced(
      clock, 3000, [](std::int64_t step) { return step == 1000 ? milliseconds(200) : microseconds(300); });
  // 199 ms behind: the 149 ticks beyond the 50 ms bound are given up, and the one under way (150)
  EXPECT_EQ(s.skipped_ticks, 150);
  EXPECT_EQ(s.catch_up_limits, 1);
  EXPECT_FALSE(s.keeping_real_time);
  EXPECT_EQ(s.steps, 3000);
  EXPECT_EQ(s.ticks, 3150);  // given-up ticks count as ticks, not as steps
  EXPECT_NEAR(clock.seconds(), 3.1493, 1e-9);
}

// Where nobody feels a millisecond the loop runs its ticks in bursts: one wake-up per burst.
TEST(LoopPacing, TicksPerWakeSleepsOncePerBurst) {
  ManualClock clock;
  const LoopStats s = run_paced(
      clock, 4000, [](std::int64_t) { return microseconds(100); }, 4);
  EXPECT_EQ(s.ticks, 4000);
  EXPECT_EQ(s.skipped_ticks, 0);
  EXPECT_EQ(clock.sleeps, 999);  // before ticks 4, 8, ... 3996
  EXPECT_NEAR(s.real_time_factor, 1.0, 1e-3);
}

// A whole session on the manual clock: the autopilot drives 12 simulated seconds, the keeper records and
// evaluates off the step thread; the recording replays bit for bit and a seek to its end starts from the
// step thread's keyframe (every 10 s).
TEST(LoopPacing, ASessionOnItsClockRecordsARunThatReplaysBitForBit) {
  const sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  ManualClock clock;
  SessionOptions options;
  options.trainee = "t1";
  options.database = scenes::fresh_database("harbour_station_paced.db");
  options.record = scenes::temp_path("harbour_station_paced.hsrc");
  options.loop.clock = &clock;
  Session session(exercise, options);
  sim::GantryAutopilot pilot(exercise);
  session.loop().set_pilot([&](const sim::Simulation& s) {
    clock.advance(microseconds(200));
    return pilot.next(s);
  });
  session.start();
  while (session.loop().stats().steps < 12000)
    std::this_thread::sleep_for(milliseconds(5));
  const SessionResult result = session.finish(SessionEnd::kInterrupted);
  const LoopStats& s = result.loop;
  EXPECT_TRUE(s.keeping_real_time);
  EXPECT_EQ(s.skipped_ticks, 0);
  EXPECT_EQ(s.late_ticks, 0);
  EXPECT_EQ(result.status, "interrupted");

  const sim::Recording recording = io::read_recording(options.record);
  EXPECT_EQ(recording.total_steps, s.steps);
  const sim::ReplayResult replay = sim::replay(exercise.scenario, recording);
  EXPECT_GE(replay.checkpoints_checked, 11);
  EXPECT_FALSE(replay.first_mismatch.has_value());
  EXPECT_EQ(recording.keyframes.size(), static_cast<std::size_t>(s.steps / sim::Recorder::kKeyframeEvery));
  const sim::ReplayResult seek = sim::replay(exercise.scenario, recording, recording.total_steps);
  EXPECT_EQ(seek.keyframes_used, 1);
  EXPECT_FALSE(seek.first_mismatch.has_value());
  std::filesystem::remove(options.record);
}

}  // namespace
}  // namespace harbour::station
