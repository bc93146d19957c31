#include "harbour/sim/Recording.h"

#include <gtest/gtest.h>

#include <limits>
#include <map>

#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/sts/StsCrane.h"
#include "scenes/StsScenes.h"

namespace harbour::sim {
namespace {

constexpr std::int64_t kRunSteps = 20000;

// the scripted run, recorded, with the hash at every step kept for comparison
struct RecordedRun {
  Recording recording;
  std::map<std::int64_t, std::uint64_t> hash_at;
  RecordedRun() {
    Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
    Recorder recorder("sts_discharge_test", scenes::sts_controls());
    for (std::int64_t k = 0; k < kRunSteps; ++k) {
      const StsControls in = scenes::scripted_operator(k);
      s.step(scenes::cab(in));
      recorder.after_step(s, scenes::cab(in));
      if (s.steps() % 100 == 0) hash_at[s.steps()] = s.state_hash();
    }
    recording = recorder.recording();
  }
};

const RecordedRun& run() {
  static const RecordedRun r;
  return r;
}

TEST(Recording, ReplayReproducesTheHashAtEveryRecordedSecond) {
  const ReplayResult r = replay(scenes::sts_discharge(HARBOUR_DATA_DIR), run().recording);
  EXPECT_EQ(r.checkpoints_checked, 20);
  EXPECT_FALSE(r.first_mismatch.has_value()) << "first mismatch at step " << *r.first_mismatch;
  EXPECT_EQ(r.simulation->steps(), kRunSteps);
  EXPECT_LT(run().recording.inputs.size(), 20u);  // only changes are stored
}

TEST(Recording, InputsAreRecordedAsTheMachineReadThem) {
  Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
  Recorder recorder("levers", scenes::sts_controls());
  StsControls in;
  in.trolley = std::numeric_limits<double>::quiet_NaN();
  in.hoist = 3.0;
  s.step(scenes::cab(in));
  recorder.after_step(s, scenes::cab(in));
  ASSERT_EQ(recorder.recording().inputs.size(), 1u);
  const scene::ControlTable& table = s.control_table();
  EXPECT_EQ(recorder.recording().inputs[0].controls, table.in_range(scenes::cab(in)));
  EXPECT_EQ(recorder.recording().inputs[0].controls.value[static_cast<std::size_t>(table.find("trolley"))],
            0.0);
  EXPECT_EQ(recorder.recording().inputs[0].controls.value[static_cast<std::size_t>(table.find("hoist"))],
            1.0);
  EXPECT_EQ(recorder.recording().control_labels[static_cast<std::size_t>(table.find("hoist"))], "hoist");
}

TEST(Recording, ATamperedRecordingIsDetected) {
  Recording tampered = run().recording;
  tampered.inputs[2].controls.value[static_cast<std::size_t>(scenes::sts_controls().find("hoist"))] += 0.01;
  const ReplayResult r = replay(scenes::sts_discharge(HARBOUR_DATA_DIR), tampered);
  ASSERT_TRUE(r.first_mismatch.has_value());
}

TEST(Recording, ASeekStartsFromAKeyframeAndLandsOnTheRecordedState) {
  EXPECT_EQ(run().recording.keyframes.size(), 2u);  // at 10 s and 20 s
  const ReplayResult r = replay(scenes::sts_discharge(HARBOUR_DATA_DIR), run().recording, 15300);
  EXPECT_EQ(r.keyframes_used, 1);
  EXPECT_EQ(r.simulation->steps(), 15300);
  EXPECT_EQ(r.simulation->state_hash(), run().hash_at.at(15300));
  EXPECT_FALSE(r.first_mismatch.has_value());
}

// The console's replay: scrubbing back and forth and playing on lands on the recorded state every time.
TEST(Recording, APlayerScrubsBackAndForthAndPlaysOnToTheRecordedStates) {
  const ScenarioSettings scenario = scenes::sts_discharge(HARBOUR_DATA_DIR);
  ReplayPlayer player(scenario, run().recording);
  for (const std::int64_t step : {15300, 4200, 4900, 19900, 10000, 12700}) {
    player.seek(step);
    ASSERT_EQ(player.simulation().steps(), step);
    EXPECT_EQ(player.simulation().state_hash(), run().hash_at.at(step)) << "at step " << step;
  }
  EXPECT_EQ(player.keyframes_used(),
            3);              // 15300 and 19900 from theirs, 10000 from its own; 4200 from the start
  player.advance_to(17000);  // play on
  EXPECT_EQ(player.simulation().state_hash(), run().hash_at.at(17000));
  player.advance_to(kRunSteps + 5000);  // stops at the end
  EXPECT_EQ(player.simulation().steps(), kRunSteps);
  EXPECT_FALSE(player.first_mismatch().has_value());
}

// The instructor changes the weather and breaks the hoist brake during a run: the recording keeps the
// commands with their steps, a replay (whole or from a keyframe) applies them again and lands on the same
// state, and the same inputs without them end elsewhere.
TEST(Recording, InstructorCommandsAreRecordedAndReplayed) {
  const ScenarioSettings scenario = scenes::sts_discharge(HARBOUR_DATA_DIR);
  Simulation s(scenario);
  Recorder recorder("commands", scenes::sts_controls());
  InstructorCommand wind;
  wind.kind = InstructorCommand::Kind::kSetWind;
  wind.wind_mean_mps = 14.0;
  wind.wind_from_rad = 1.5 * 3.14159265358979;  // from the west: across the quay
  wind.turbulence = 0.1;
  InstructorCommand gust;
  gust.gust = {0.0, 3.0, 9.0};
  InstructorCommand fog;
  fog.kind = InstructorCommand::Kind::kSetVisibility;
  fog.value = 300.0;
  for (std::int64_t k = 0; k < kRunSteps; ++k) {
    if (k == 3000 || k == 9000 || k == 12500) {
      const InstructorCommand& c = k == 3000 ? wind : k == 9000 ? gust : fog;
      s.command(c);
      recorder.on_command(s, c);
    }
    const StsControls in = scenes::scripted_operator(k);
    s.step(scenes::cab(in));
    recorder.after_step(s, scenes::cab(in));
  }
  EXPECT_EQ(s.snapshot()->visibility_m, 300.0);
  const Recording& recording = recorder.recording();
  ASSERT_EQ(recording.commands.size(), 3u);

  const ReplayResult whole = replay(scenario, recording);
  EXPECT_FALSE(whole.first_mismatch.has_value()) << "first mismatch at step " << *whole.first_mismatch;
  EXPECT_EQ(whole.simulation->state_hash(), s.state_hash());
  EXPECT_EQ(whole.simulation->snapshot()->visibility_m, 300.0);

  const ReplayResult seek = replay(scenario, recording, 19000);  // from the 10 s keyframe: fog still to come
  EXPECT_EQ(seek.keyframes_used, 1);
  EXPECT_FALSE(seek.first_mismatch.has_value());
  EXPECT_EQ(seek.simulation->snapshot()->visibility_m, 300.0);

  Recording without = recording;
  without.commands.clear();
  EXPECT_TRUE(replay(scenario, without).first_mismatch.has_value());

  // dusk on request: the clock jumps there and runs on
  InstructorCommand dusk;
  dusk.kind = InstructorCommand::Kind::kSetTimeOfDay;
  dusk.value = 21.5;
  s.command(dusk);
  for (int k = 0; k < 36000; ++k)
    s.step({});
  EXPECT_NEAR(s.snapshot()->time_of_day_h, 21.51, 1e-9);

  // a command out of range changes nothing
  InstructorCommand bad;
  bad.kind = InstructorCommand::Kind::kLandedSensorFault;
  bad.corner = 7;
  const std::uint64_t before = s.state_hash();
  EXPECT_THROW(s.command(bad), std::invalid_argument);
  EXPECT_EQ(s.state_hash(), before);
}

// Instructor commands that change the crane: with the hoist brake broken an emergency stop lets the spreader
// run down; once the instructor clears the faults the brake holds it again.
TEST(Recording, TheInstructorBreaksAndRepairsTheHoistBrake) {
  Simulation s(scenes::sts_discharge(HARBOUR_DATA_DIR));
  for (int k = 0; k < 3000; ++k)
    s.step({});
  StsControls stop;
  stop.emergency_stop = true;
  auto drop_under_estop = [&] {
    const double z0 = s.machine_as<StsCrane>().spreader_pose().position.z;
    for (int k = 0; k < 2000; ++k)
      s.step(scenes::cab(stop));
    return s.machine_as<StsCrane>().spreader_pose().position.z - z0;
  };
  InstructorCommand fault;
  fault.kind = InstructorCommand::Kind::kHoistBrakeFault;
  s.command(fault);
  EXPECT_LT(drop_under_estop(), -1.0);
  InstructorCommand repair;
  repair.kind = InstructorCommand::Kind::kClearFaults;
  s.command(repair);
  for (int k = 0; k < 15000; ++k)  // the ropes stop bouncing after the run-down
    s.step({});
  EXPECT_NEAR(drop_under_estop(), 0.0, 0.01);
}

TEST(Recording, ARestoredStateContinuesBitForBitWhileCarryingABox) {
  // the autopilot's run, saved while the box hangs from the spreader and the truck waits
  const ExerciseSettings e = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  Simulation original(e.scenario);
  GantryAutopilot pilot(e);
  std::vector<std::uint8_t> saved;
  GantryAutopilot pilot_at_save(e);
  while (original.time_s() < 60.0) {
    if (original.steps() == 50000) {
      ASSERT_TRUE(original.machine_as<StsCrane>().locked_container().has_value());
      saved = original.save_state();
      pilot_at_save = pilot;
    }
    original.step(pilot.next(original));
  }
  Simulation restored(e.scenario);
  restored.restore_state(saved);
  EXPECT_TRUE(restored.machine_as<StsCrane>().locked_container().has_value());
  EXPECT_FALSE(restored.secured(1));  // the lifted box stays released
  while (restored.time_s() < 60.0)
    restored.step(pilot_at_save.next(restored));
  EXPECT_EQ(restored.state_hash(), original.state_hash());

  // a state from another world is refused, naming the part that differs
  ScenarioSettings other = e.scenario;
  other.containers.pop_back();
  Simulation elsewhere(other);
  EXPECT_THROW(elsewhere.restore_state(saved), core::StateError);
}

TEST(Recording, TakeOverContinuesFromExactlyTheRecordedState) {
  const std::int64_t at = 7300;  // mid-lowering
  TakeOver t = take_over(scenes::sts_discharge(HARBOUR_DATA_DIR), run().recording, "attempt-1", at);
  EXPECT_EQ(t.simulation->steps(), at);
  EXPECT_EQ(t.simulation->state_hash(), run().hash_at.at(at));

  // the instructor raises the spreader instead; the branch is its own recording, linked to the original
  StsControls raise;
  raise.hoist = 0.5;
  for (int k = 0; k < 3000; ++k) {
    t.simulation->step(scenes::cab(raise));
    t.recorder.after_step(*t.simulation, scenes::cab(raise));
  }
  const Recording& branch = t.recorder.recording();
  EXPECT_EQ(branch.parent, "attempt-1");
  EXPECT_EQ(branch.branch_step, at);
  EXPECT_NE(t.simulation->state_hash(), run().hash_at.at(at + 3000));
  const ReplayResult again = replay(scenes::sts_discharge(HARBOUR_DATA_DIR), branch);
  EXPECT_FALSE(again.first_mismatch.has_value());
  EXPECT_EQ(again.simulation->state_hash(), t.simulation->state_hash());
}

}  // namespace
}  // namespace harbour::sim
