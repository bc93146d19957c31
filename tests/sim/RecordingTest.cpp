#include "harbour/sim/Recording.h"

#include <gtest/gtest.h>

#include <map>

#include "harbour/sim/Autopilot.h"
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
    Recorder recorder("sts_discharge_test");
    for (std::int64_t k = 0; k < kRunSteps; ++k) {
      const Inputs in = scenes::scripted_operator(k);
      s.step(in);
      recorder.after_step(s, in);
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

TEST(Recording, ATamperedRecordingIsDetected) {
  Recording tampered = run().recording;
  tampered.inputs[2].inputs.sts.hoist += 0.01;
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

TEST(Recording, ARestoredStateContinuesBitForBitWhileCarryingABox) {
  // the autopilot's run, saved while the box hangs from the spreader and the truck waits
  const ExerciseSettings e = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  Simulation original(e.scenario);
  Autopilot pilot(e);
  std::vector<std::uint8_t> saved;
  Autopilot pilot_at_save(e);
  while (original.time_s() < 60.0) {
    if (original.steps() == 50000) {
      ASSERT_TRUE(original.crane().locked_container().has_value());
      saved = original.save_state();
      pilot_at_save = pilot;
    }
    original.step(pilot.next(original));
  }
  Simulation restored(e.scenario);
  restored.restore_state(saved);
  EXPECT_TRUE(restored.crane().locked_container().has_value());
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
  Inputs raise;
  raise.sts.hoist = 0.5;
  for (int k = 0; k < 3000; ++k) {
    t.simulation->step(raise);
    t.recorder.after_step(*t.simulation, raise);
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
