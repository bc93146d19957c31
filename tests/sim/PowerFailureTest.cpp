// The instructor's power failure: the supply fails while the STS hoists a box; its drives stop on their
// emergency ramp and hold, the box bouncing on the ropes about where it was. When the supply is back, nothing
// moves while a lever is held off zero (zero-voltage protection); once every lever has been centred, the
// drives answer again.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/sim/Pilot.h"

namespace harbour::sim {
namespace {

InstructorCommand command(InstructorCommand::Kind kind) {
  InstructorCommand c;
  c.kind = kind;
  return c;
}

struct Carrying {
  ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  Simulation sim{exercise.scenario};
  scene::Controls hoist_up;  // a trainee holding the hoist lever up, nothing else
  Carrying() {
    // the autopilot picks the box up and carries it 3 m above where it stood
    GantryAutopilot pilot(exercise);
    double lifted_from_z = 0.0;
    for (int k = 0; k < 300000; ++k) {
      sim.step(pilot.next(sim));
      if (!sim.machine_as<StsCrane>().locked_container()) continue;
      if (lifted_from_z == 0.0) lifted_from_z = sim.machine_as<StsCrane>().spreader_pose().position.z;
      if (sim.machine_as<StsCrane>().spreader_pose().position.z > lifted_from_z + 3.0) break;
    }
    hoist_up = sim.control_table().neutral();
    hoist_up.value[static_cast<std::size_t>(sim.control_table().find("hoist"))] = 0.5;
  }
  // Steps `seconds` with the same controls: the spreader's mean and lowest height over them, the trolley's
  // position at the end.
  struct Run {
    double mean_z = 0.0, lowest_z = 1e9, trolley_x = 0.0;
  };
  Run run(const scene::Controls& in, double seconds) {
    Run r;
    const int steps = static_cast<int>(std::lround(seconds / Simulation::kStep_s));
    for (int k = 0; k < steps; ++k) {
      sim.step(in);
      const double z = sim.machine_as<StsCrane>().spreader_pose().position.z;
      r.mean_z += z / steps;
      r.lowest_z = std::min(r.lowest_z, z);
    }
    r.trolley_x = sim.machine_as<StsCrane>().trolley_x_m();
    return r;
  }
};

// the box's bounce on the ropes after the drum stops hoisting: about 2.2 s
constexpr double kTwoBounces_s = 4.4;

TEST(PowerFailure, TheDrivesStopAndHoldAndNothingRestartsUnderAHeldLever) {
  Carrying crane;
  ASSERT_TRUE(crane.sim.machine_as<StsCrane>().locked_container()) << "the autopilot lifted no box";
  Simulation& sim = crane.sim;
  sim.command(command(InstructorCommand::Kind::kPowerFailure));
  EXPECT_TRUE(sim.power_off());
  // the trainee pulls the hoist lever: dead drives; the box bounces on the ropes about a fixed height
  const double cut_z = sim.machine_as<StsCrane>().spreader_pose().position.z;
  const auto first = crane.run(crane.hoist_up, 1.0);
  const auto a = crane.run(crane.hoist_up, kTwoBounces_s);
  const auto b = crane.run(crane.hoist_up, kTwoBounces_s);
  EXPECT_LT(std::abs(b.mean_z - a.mean_z), 0.03) << "the box crept " << b.mean_z - a.mean_z << " m";
  EXPECT_GT(std::min(a.lowest_z, b.lowest_z), cut_z - 0.3) << "the box fell";
  EXPECT_LT(std::abs(b.trolley_x - first.trolley_x), 0.01) << "the trolley moved with the power off";
  EXPECT_TRUE(sim.machine_as<StsCrane>().locked_container());
  auto snapshot = std::make_unique<scene::Snapshot>();
  sim.write_snapshot(*snapshot);
  EXPECT_TRUE(snapshot->power_off);

  // the supply is back with the lever still held: nothing moves
  sim.command(command(InstructorCommand::Kind::kPowerRestored));
  EXPECT_FALSE(sim.power_off());
  EXPECT_TRUE(sim.awaiting_zero());
  const auto c = crane.run(crane.hoist_up, kTwoBounces_s);
  EXPECT_LT(std::abs(c.mean_z - b.mean_z), 0.03) << "the hoist restarted under a held lever";
  EXPECT_TRUE(sim.awaiting_zero());
  sim.write_snapshot(*snapshot);
  EXPECT_TRUE(snapshot->awaiting_zero);
  EXPECT_FALSE(snapshot->power_off);

  // a lever just inside the zero band counts as centred; then the hoist answers the lever again
  scene::Controls nearly = sim.control_table().neutral();
  nearly.value[static_cast<std::size_t>(sim.control_table().find("hoist"))] =
      0.9 * Simulation::kLeverZeroBand;
  crane.run(nearly, 0.01);
  EXPECT_FALSE(sim.awaiting_zero());
  const auto d = crane.run(crane.hoist_up, kTwoBounces_s);
  EXPECT_GT(d.mean_z - c.mean_z, 0.5) << "the hoist did not answer after the levers were centred";
  EXPECT_TRUE(sim.machine_as<StsCrane>().locked_container());
}

// A keyframe taken while the drives wait for zero restores the wait: both go on bit for bit, and a state
// from before the power failure hashes as it did (no flags set, nothing added).
TEST(PowerFailure, AKeyframeKeepsTheOutageAndTheWaitForZero) {
  Carrying crane;
  Simulation& sim = crane.sim;
  const std::uint64_t before = sim.state_hash();
  sim.command(command(InstructorCommand::Kind::kPowerFailure));
  EXPECT_NE(sim.state_hash(), before) << "the outage is part of the state";
  crane.run(crane.hoist_up, 1.0);
  sim.command(command(InstructorCommand::Kind::kPowerRestored));
  crane.run(crane.hoist_up, 0.5);
  Simulation copy(crane.exercise.scenario);
  copy.restore_state(sim.save_state());
  EXPECT_TRUE(copy.awaiting_zero());
  EXPECT_EQ(copy.state_hash(), sim.state_hash());
  const scene::Controls neutral = sim.control_table().neutral();
  for (int k = 0; k < 2000; ++k) {
    const scene::Controls& in = k < 1000 ? crane.hoist_up : (k < 1010 ? neutral : crane.hoist_up);
    sim.step(in);
    copy.step(in);
  }
  EXPECT_FALSE(copy.awaiting_zero());
  EXPECT_EQ(copy.state_hash(), sim.state_hash());
}

// The scripted operator takes its hands off the levers for the outage and finishes the exercise after it.
TEST(PowerFailure, TheScriptedOperatorWaitsItOutAndFinishes) {
  const ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  Simulation sim(exercise.scenario);
  const std::unique_ptr<Pilot> pilot = make_pilot(exercise);
  Evaluator evaluator(exercise);
  bool held_off_when_back = true;
  for (int k = 0; k < 400000 && !evaluator.finished(); ++k) {
    if (k == 35000) sim.command(command(InstructorCommand::Kind::kPowerFailure));
    if (k == 45000) sim.command(command(InstructorCommand::Kind::kPowerRestored));
    const scene::Controls in = pilot->next(sim);
    if (k == 45000) held_off_when_back = in == sim.control_table().neutral();
    sim.step(in);
    evaluator.observe(sim, in);
  }
  EXPECT_TRUE(held_off_when_back) << "the pilot's hands were on the levers as the power came back";
  EXPECT_FALSE(sim.awaiting_zero());
  EXPECT_TRUE(evaluator.finished());
  EXPECT_EQ(evaluator.metrics().moves_completed, 1);
  EXPECT_TRUE(evaluator.score().passed) << evaluator.score().total;
}

TEST(PowerFailure, TheCommandLineAndTheConsoleNameIt) {
  EXPECT_EQ(io::parse_instructor_command("12.5:power-failure").command.kind,
            InstructorCommand::Kind::kPowerFailure);
  EXPECT_EQ(io::parse_instructor_command("40:power-restored").command.kind,
            InstructorCommand::Kind::kPowerRestored);
  EXPECT_THROW(io::parse_instructor_command("40:power-restored:1"), std::invalid_argument);
}

}  // namespace
}  // namespace harbour::sim
