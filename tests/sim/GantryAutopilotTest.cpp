#include "harbour/machines/GantryAutopilot.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "harbour/core/Units.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/sim/Recording.h"
#include "scenes/StsScenes.h"

namespace harbour::sim {
namespace {

struct Attempt {
  Metrics metrics;
  Score score;
  bool done = false;
};

ExerciseSettings shipped(const std::string& exercise_file) {
  return io::load_exercise(HARBOUR_DATA_DIR "/exercises/" + exercise_file);
}

Attempt run(const ExerciseSettings& exercise, OperatorDefects defects = {}, int max_steps = 240000) {
  Simulation sim(exercise.scenario);
  GantryAutopilot pilot(exercise, defects);
  Evaluator evaluator(exercise);
  for (int k = 0; k < max_steps && !evaluator.finished(); ++k) {
    const scene::Controls in = pilot.next(sim);
    sim.step(in);
    evaluator.observe(sim, in);
  }
  EXPECT_EQ(sim.warnings().total(), 0u);
  return {evaluator.metrics(), evaluator.score(), evaluator.finished()};
}

Attempt run(OperatorDefects defects = {}, const std::string& exercise_file = "sts_discharge.yaml") {
  return run(shipped(exercise_file), defects);
}

TEST(GantryAutopilot, CompletesTheDischargeWithAPassingScore) {
  const Attempt a = run();
  ASSERT_TRUE(a.done) << "moves " << a.metrics.moves_completed << " after " << a.metrics.time_s << " s";
  EXPECT_TRUE(a.score.passed);
  EXPECT_EQ(a.score.total, 100.0) << a.score.deductions.front().reason;
  EXPECT_EQ(a.metrics.collisions, 0);
  EXPECT_EQ(a.metrics.hard_landings, 0);
  EXPECT_EQ(a.metrics.sway_landings, 0);
  ASSERT_EQ(a.metrics.landing_sway_m.size(), 2u);  // pick-up and set-down
  EXPECT_LT(a.metrics.time_s, 180.0);
  EXPECT_GT(a.metrics.hoist_energy_j, 0.0);
  // the trolley (30 t) at least was brought up to speed and back: more than its kinetic energy at 1 m/s
  EXPECT_GT(a.metrics.travel_energy_j, 0.5 * 30000.0 * 1.0 * 1.0);
  // driven as smoothly as every other crane is measured: its gantry, trolley and hoist, the trolley and hoist
  // moved (the gantry stood)
  ASSERT_EQ(a.metrics.smoothness.size(), 3u);
  EXPECT_EQ(a.metrics.smoothness[0].axis, "gantry");
  EXPECT_EQ(a.metrics.smoothness[1].axis, "trolley");
  EXPECT_EQ(a.metrics.smoothness[2].axis, "hoist");
  EXPECT_GT(a.metrics.smoothness[1].rms_jerk_mps3, 0.0);
  EXPECT_GT(a.metrics.smoothness[2].rms_jerk_mps3, 0.0);
  std::printf("sts smoothness: trolley %.3f m/s^3 (%d harsh), hoist %.3f m/s^3 (%d harsh)\n",
              a.metrics.smoothness[1].rms_jerk_mps3, a.metrics.smoothness[1].harsh_moves,
              a.metrics.smoothness[2].rms_jerk_mps3, a.metrics.smoothness[2].harsh_moves);
  RecordProperty("cycle_time_s", std::to_string(a.metrics.cycle_times_s.front()));
}

// A fresh breeze along the quay (10 m/s, 15 % turbulence) with a 3 s gust of +8 m/s while the box travels,
// and a swell rolling the feeder (the box to pick up moves some 2.5 cm across): the autopilot catches the
// swing, follows the box and lands within the twistlocks' reach.
TEST(GantryAutopilot, LandsInAGustyCrosswindOnARollingShip) {
  const Attempt a = run({}, "sts_discharge_gusty.yaml");
  ASSERT_TRUE(a.done) << "moves " << a.metrics.moves_completed << " after " << a.metrics.time_s << " s";
  EXPECT_TRUE(a.score.passed);
  EXPECT_EQ(a.metrics.collisions, 0);
  EXPECT_EQ(a.metrics.hard_landings, 0);
  EXPECT_EQ(a.metrics.twistlock_misuse, 0);
  EXPECT_LT(a.metrics.time_s, 180.0);  // the exercise's time limit
}

// A steady 12 m/s wind across the quay leans the hanging spreader some 0.2 m off plumb: landings there are
// not swaying (sway is measured from the rest position in the mean wind), and the autopilot, leaning into
// the wind, lands as calmly as in still air. With 15 % turbulence it still clears the move.
TEST(GantryAutopilot, LandsInAStrongCrossQuayWindWithoutCountingTheLeanAsSway) {
  ExerciseSettings exercise = shipped("sts_discharge.yaml");
  exercise.scenario.weather.wind_mean_mps = 12.0;
  exercise.scenario.weather.wind_from_rad = core::deg_to_rad(270.0);  // from the land side, towards +x
  {
    Simulation still(exercise.scenario);  // the spreader swings about its leaning rest position
    double mean_offset = 0.0;
    constexpr int kSteps = 40000;  // four periods
    for (int k = 0; k < kSteps; ++k) {
      still.step({});
      mean_offset += (still.machine_as<StsCrane>().spreader_pose().position.x -
                      still.machine_as<StsCrane>().trolley_position_m()) /
                     kSteps;
    }
    const core::Vec3 lean = still.wind_rest_offset_m(still.weather().mean_wind(), std::nullopt);
    EXPECT_GT(lean.x, 0.15);
    EXPECT_NEAR(mean_offset, lean.x, 0.03);
  }
  Attempt a = run(exercise);
  ASSERT_TRUE(a.done);
  EXPECT_EQ(a.score.total, 100.0);
  ASSERT_EQ(a.metrics.landing_sway_m.size(), 2u);
  for (const double sway : a.metrics.landing_sway_m)
    EXPECT_LT(sway, 0.05);
  EXPECT_LT(a.metrics.time_s, 180.0);

  exercise.scenario.weather.turbulence_intensity = 0.15;
  a = run(exercise);
  ASSERT_TRUE(a.done);
  EXPECT_TRUE(a.score.passed);
  EXPECT_EQ(a.metrics.collisions + a.metrics.hard_landings + a.metrics.twistlock_misuse, 0);
  EXPECT_LT(a.metrics.time_s, 240.0);  // it waited 530 s for a calm moment when it ignored the gusts
}

// Opening a hold: two deck boxes to the trucks, the 20 t hatch cover to the quay, two boxes up through the
// cell guides (25 mm clearance a side) to the trucks.
TEST(GantryAutopilot, OpensAHoldAndDischargesThroughTheCellGuides) {
  const Attempt a = run(shipped("sts_bay12_hold.yaml"), {}, 1080000);
  ASSERT_TRUE(a.done) << "moves " << a.metrics.moves_completed << " after " << a.metrics.time_s << " s";
  EXPECT_EQ(a.metrics.moves_completed, 5);
  EXPECT_TRUE(a.score.passed);
  EXPECT_EQ(a.score.total, 100.0) << a.score.deductions.front().reason;
  EXPECT_EQ(a.metrics.collisions, 0);  // no spreader on a cell guide, no box on a neighbour
  EXPECT_EQ(a.metrics.cell_guide_collisions, 0);
  EXPECT_EQ(a.metrics.twistlock_misuse, 0);
  EXPECT_EQ(a.metrics.landing_sway_m.size(), 10u);  // a pick-up and a set-down per move
  RecordProperty("moves_per_hour", std::to_string(a.metrics.moves_per_hour));
}

TEST(GantryAutopilot, ABadOperatorGetsTheDocumentedPenalties) {
  const Attempt a = run({.land_fast = true, .forget_lock_once = true});
  ASSERT_TRUE(a.done);
  EXPECT_EQ(a.metrics.hard_landings, 1);
  EXPECT_EQ(a.metrics.twistlock_misuse, 1);
  const EvaluationRules rules;
  EXPECT_DOUBLE_EQ(a.score.total, 100.0 - rules.points_hard_landing - rules.points_twistlock_misuse);
}

TEST(Evaluation, HittingABoxThatIsNotTheTaskIsACollision) {
  // the task is TGHU1000010; the operator drives the empty spreader down fast onto TGHU1000012 right below it
  ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  exercise.moves[0].container_id = "TGHU1000010";
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  StsControls drop;
  drop.hoist = -0.6;  // 0.9 m/s at the spreader
  // the impact is reported when its impulse window closes: compare with the speed just before it began
  std::vector<double> speeds;
  for (int k = 0; k < 20000 && evaluator.metrics().collisions == 0; ++k) {
    speeds.push_back(-sim.world().linear_velocity(sim.machine_as<StsCrane>().spreader_body()).z);
    sim.step(scenes::cab(drop));
    evaluator.observe(sim, scenes::cab(drop));
  }
  ASSERT_GT(speeds.size(), static_cast<std::size_t>(physics::PhysicsWorld::kImpulseWindowSteps));
  const double speed = speeds[speeds.size() - physics::PhysicsWorld::kImpulseWindowSteps];
  EXPECT_EQ(evaluator.metrics().collisions, 1);
  EXPECT_EQ(evaluator.metrics().container_collisions, 1);  // spreader on a box
  // the impulse stops the 15 t spreader from its impact speed (and carries it for the rest of the window)
  EXPECT_GT(evaluator.metrics().collision_impulse_ns, 0.8 * 15000 * speed);
  EXPECT_LT(evaluator.metrics().collision_impulse_ns, 1.2 * 15000 * speed + 15000 * 9.81 * 0.005);
  EXPECT_NEAR(evaluator.metrics().worst_collision_mps, speed, 0.1);
  EXPECT_GT(speed, 0.5);
  const core::Vec3 at = sim.machine_as<StsCrane>().spreader_pose().position;  // on TGHU1000012's top
  EXPECT_NEAR(at.y, 0.0, 0.1);
  EXPECT_NEAR(at.z, 3.3 + 2.591 + 0.5, 0.1);
  EXPECT_EQ(evaluator.score().total,
            100.0 - exercise.rules.points_collision - exercise.rules.points_per_move_missing);
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

// drives the gantry 0.5 lever for `steps`, the horn sounding for the first `horn_steps`
Evaluator travel_gantry(int horn_steps, int steps) {
  const ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  for (int k = 0; k < steps; ++k) {
    StsControls in;
    in.horn = k < horn_steps;
    in.gantry = k >= 1000 ? 0.5 : 0.0;
    sim.step(scenes::cab(in));
    evaluator.observe(sim, scenes::cab(in));
  }
  return evaluator;
}

TEST(Evaluation, GantryTravelWithoutTheHornCountsAgainstSafety) {
  // 0.375 m/s after a 2.5 s ramp: 1 m is covered after about 4 s, 2.4 m after 8 s
  const Evaluator silent = travel_gantry(0, 9000);
  EXPECT_EQ(silent.metrics().unwarned_gantry_travel, 1);
  const Score s = silent.score();
  const EvaluationRules rules;
  ASSERT_FALSE(s.deductions.empty());
  EXPECT_EQ(s.deductions.front().reason, "gantry travel without the horn");
  EXPECT_EQ(s.deductions.front().skill, Skill::kSafety);
  EXPECT_DOUBLE_EQ(s.skills[static_cast<std::size_t>(Skill::kSafety)], 100.0 - rules.points_unwarned_travel);
  // the moves not made count against productivity alone
  EXPECT_DOUBLE_EQ(s.skills[static_cast<std::size_t>(Skill::kProductivity)],
                   100.0 - rules.points_per_move_missing);
  EXPECT_DOUBLE_EQ(s.skills[static_cast<std::size_t>(Skill::kPrecision)], 100.0);

  EXPECT_EQ(travel_gantry(500, 9000).metrics().unwarned_gantry_travel, 0);  // horn 0.5 s before moving
  EXPECT_EQ(travel_gantry(0, 3000).metrics().unwarned_gantry_travel, 0);    // a creep under 1 m
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

TEST(Evaluation, ASpreaderLoweredOffTheCellCountsACellGuideCollision) {
  // bay 12 with its hatch covers off and its cells empty; row 01's cell is centred at x = 32.27 m. The
  // spreader comes down 15 cm off to waterside (the guides leave 25 mm a side) and lands on the guides.
  ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  exercise.scenario.containers.clear();
  exercise.scenario.machine.as<StsSetup>().trolley_x_m = 32.27 + 0.15;
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  StsControls lower;
  lower.hoist = -0.6;
  for (int k = 0; k < 40000 && evaluator.metrics().collisions == 0; ++k) {
    sim.step(scenes::cab(lower));
    evaluator.observe(sim, scenes::cab(lower));
  }
  EXPECT_EQ(evaluator.metrics().collisions, 1);
  EXPECT_EQ(evaluator.metrics().cell_guide_collisions, 1);
  // it stopped on the guides' tops, above the hold
  const Vessel& vessel = *sim.vessel();
  const double coaming = vessel.frame().to_parent({0, 0, vessel.geometry().coaming_top_m()}).z;
  EXPECT_GT(sim.machine_as<StsCrane>().spreader_pose().position.z, coaming - 0.5);
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

class TakeOverAt : public ::testing::TestWithParam<std::int64_t> {};

// The original attempt is recorded up to the take-over (30 s: the spreader on its way down to the box; 62 s:
// the box travelling to the truck, swinging, the trolley lever at -0.6); the instructor takes over there: the
// branch's evaluator sees the history, the autopilot drives on (catching the swing) and finishes. Its hands
// start from the levers as they stood: over the first second no lever jumps further than a hand moves one in
// a decision (full travel in a second: 0.02 in 20 ms).
INSTANTIATE_TEST_SUITE_P(Moments, TakeOverAt, ::testing::Values(30000, 62000));

TEST_P(TakeOverAt, AnInstructorTakeOverContinuesTheAttemptFromTheRecordedState) {
  const std::int64_t at = GetParam();
  const ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  Recorder recorder(exercise.name, scenes::sts_controls());
  {
    Simulation sim(exercise.scenario);
    GantryAutopilot pilot(exercise);
    for (std::int64_t k = 0; k < at; ++k) {
      const scene::Controls in = pilot.next(sim);
      sim.step(in);
      recorder.after_step(sim, in);
    }
  }
  Evaluator evaluator(exercise);
  int observed = 0;
  TakeOver branch = take_over(exercise.scenario, recorder.recording(), "original", at,
                              [&](const Simulation& s, const scene::Controls& in) {
                                evaluator.observe(s, in);
                                ++observed;
                              });
  EXPECT_EQ(observed, at);  // every step of the history, not a keyframe jump
  EXPECT_EQ(branch.recorder.recording().parent, "original");
  EXPECT_EQ(branch.recorder.recording().branch_step, at);
  GantryAutopilot pilot(exercise);
  pilot.resume(*branch.simulation, evaluator.metrics().moves_completed, branch.levers);
  const scene::ControlTable& table = branch.simulation->control_table();
  scene::Controls before = branch.levers;
  double most_moved = 0.0, most_off_neutral = 0.0;  // axis levers only: buttons and switches snap
  for (int slot = 0; slot < table.size(); ++slot)
    if (table[slot].kind == scene::ControlKind::kAxis)
      most_off_neutral = std::max(most_off_neutral, std::abs(before.value[static_cast<std::size_t>(slot)]));
  for (int k = 0; k < 200000 && !evaluator.finished(); ++k) {
    const scene::Controls in = pilot.next(*branch.simulation);
    for (int slot = 0; slot < table.size(); ++slot) {
      const auto n = static_cast<std::size_t>(slot);
      if (table[slot].kind == scene::ControlKind::kAxis && k < 1000)  // the first second
        most_moved = std::max(most_moved, std::abs(in.value[n] - before.value[n]));
    }
    before = in;
    branch.simulation->step(in);
    evaluator.observe(*branch.simulation, in);
  }
  if (at == 62000) {
    EXPECT_GT(most_off_neutral, 0.5);  // the take-over finds a lever pushed
  }
  EXPECT_LE(most_moved, 0.02 + 1e-4);  // one hand step, at the lever's 16-bit resolution
  std::printf("taken over at %.0f s, a lever at %.2f: the largest lever step %.4f\n",
              static_cast<double>(at) * 1e-3, most_off_neutral, most_moved);
  EXPECT_TRUE(evaluator.finished());
  EXPECT_TRUE(evaluator.score().passed);
  EXPECT_EQ(evaluator.metrics().collisions, 0);
}

}  // namespace
}  // namespace harbour::sim
