#include <gtest/gtest.h>

#include <cmath>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/mhc/GrabAutopilot.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"
#include "harbour/sim/Recording.h"

namespace harbour::sim {
namespace {

ExerciseSettings discharge() {
  return io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_coal_discharge.yaml");
}

struct Attempt {
  Metrics metrics;
  Score score;
  bool finished = false;
  double worst_discrepancy_m3 = 0.0;  // of the bulk's volume balance, checked every second
  double added_m3 = 0.0;
  int bites = 0;
  double back_in_hold_t = 0.0;  // let go of over the hold (shells jittering open on the way up)
  double in_flight_t = 0.0;
};

Attempt drive(const ExerciseSettings& exercise, GrabOperatorDefects defects, double limit_s) {
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  GrabAutopilot pilot(exercise, defects);
  Attempt a;
  const auto steps = static_cast<std::int64_t>(limit_s / Simulation::kStep_s);
  for (std::int64_t k = 0; k < steps && !evaluator.finished(); ++k) {
    const scene::Controls c = pilot.next(sim);
    sim.step(c);
    evaluator.observe(sim, c);
    if (k % 1000 == 0) {
      const bulk::VolumeBalance b = sim.bulk()->balance();
      a.worst_discrepancy_m3 = std::max(a.worst_discrepancy_m3, std::abs(b.discrepancy_m3()));
    }
    EXPECT_FALSE(sim.diverged());
  }
  a.added_m3 = sim.bulk()->balance().added_m3;
  const double t_per_m3 = sim.bulk()->material().bulk_density_kg_m3 / 1000.0;
  a.back_in_hold_t = sim.bulk()->landed_m3(0) * t_per_m3;
  a.in_flight_t = sim.bulk()->balance().in_flight_m3 * t_per_m3;
  a.metrics = evaluator.metrics();
  a.score = evaluator.score();
  a.finished = evaluator.finished();
  a.bites = pilot.bites();
  return a;
}

double limit_of(const ExerciseSettings& exercise) {
  return exercise.rules.time_limit_s + exercise.rules.overtime_s;
}

double deducted(const Score& score, const std::string& reason) {
  double points = 0.0;
  for (const Score::Deduction& d : score.deductions)
    if (d.reason == reason) points += d.points;
  return points;
}

TEST(MhcDischarge, TheAutopilotClearsTheExerciseAndMassIsExactOverTheRun) {
  // dig in the vessel's hold, hoist clear of the coaming, slew and luff to the hopper, open, return until the
  // goal's tonnes are in: every bite that leaves the hold arrives in the hopper; hold, grab, air, hopper, its
  // outlet and the spill add up
  const ExerciseSettings exercise = discharge();
  const Attempt a = drive(exercise, {}, limit_of(exercise));
  ASSERT_TRUE(a.finished);
  EXPECT_LE(a.metrics.time_s, exercise.rules.time_limit_s);
  EXPECT_GE(a.metrics.delivered_t, exercise.deliver->tonnes);
  // full bites off a level fill: the jaws' arc and the grab's weight take the rated volume
  ASSERT_GE(a.metrics.bite_fill.size(), 3u);
  for (const double fill : a.metrics.bite_fill)
    EXPECT_GT(fill, 0.8);
  // what left the grab landed in the hopper, back in the hold, is falling or was spilled
  EXPECT_NEAR(a.metrics.delivered_t + a.back_in_hold_t + a.in_flight_t + a.metrics.spilled_t,
              a.metrics.handled_t, 1e-9 * a.metrics.handled_t);
  EXPECT_LT(a.metrics.spilled_percent, 1.0);
  EXPECT_LT(a.worst_discrepancy_m3, 1e-9 * a.added_m3);
  // a clean run: the ropes within their working load, the pads down, the limiter never stopping it
  EXPECT_EQ(a.metrics.ship_collisions, 0);
  EXPECT_EQ(a.metrics.overloads, 0);
  EXPECT_EQ(a.metrics.pad_lift_offs, 0);
  EXPECT_EQ(a.metrics.limiter_trips, 0);
  EXPECT_EQ(a.metrics.swinging_releases, 0);
  ASSERT_EQ(a.metrics.smoothness.size(), 2u);  // slew and luff, each with its jerk
  EXPECT_GT(a.metrics.smoothness[0].rms_jerk_mps3, 0.0);
  EXPECT_TRUE(a.score.passed);
  EXPECT_GE(a.score.total, exercise.rules.pass_score);
  double all = 0.0;
  for (const Score::Deduction& d : a.score.deductions)
    all += d.points;
  EXPECT_NEAR(a.score.total, std::max(0.0, 100.0 - all), 1e-9);
  bool has_delivered = false;
  for (const auto& [name, value] : a.metrics.rows())
    has_delivered |= name == "delivered_t" && value == a.metrics.delivered_t;
  EXPECT_TRUE(has_delivered);
  double swing = 0.0;
  for (const double m : a.metrics.release_swing_m)
    swing = std::max(swing, m);
  std::printf("discharge: %.1f s, %.2f t (%.0f t/h), bites", a.metrics.time_s, a.metrics.delivered_t,
              a.metrics.tonnes_per_hour);
  for (const double fill : a.metrics.bite_fill)
    std::printf(" %.0f %%", 100.0 * fill);
  std::printf(", %.2f t back in the hold, worst release swing %.2f m, score %.0f", a.back_in_hold_t, swing,
              a.score.total);
  for (const Score::Deduction& d : a.score.deductions)
    std::printf("; %s -%.0f", d.reason.c_str(), d.points);
  std::printf("\n");
}

TEST(MhcDischarge, OpeningOverTheQuayEdgeSpillsAndCosts) {
  // the bad operator opens the loaded grab on its way, over the gap between ship and quay: that coal is in
  // the water or on the quay, counted as spilled and deducted per tonne
  const ExerciseSettings exercise = discharge();
  const Attempt a = drive(exercise, {.open_over_the_quay_edge = true}, 200.0);
  EXPECT_GT(a.metrics.spilled_t, 1.0);
  std::printf("opening over the quay edge: %.2f t spilled of %.2f t handled\n", a.metrics.spilled_t,
              a.metrics.handled_t);
  EXPECT_NEAR(deducted(a.score, "tonne spilled"),  // per tonne begun
              std::ceil(a.metrics.spilled_t) * exercise.rules.points_per_spilled_t, 1e-9);
  EXPECT_NEAR(a.metrics.delivered_t + a.back_in_hold_t + a.in_flight_t + a.metrics.spilled_t,
              a.metrics.handled_t, 1e-9 * a.metrics.handled_t);
}

TEST(MhcDischarge, TravellingBelowTheCoamingHitsTheShip) {
  // slewing back into the hold with the grab below the coaming's top strikes the coaming: a ship collision,
  // deducted as a collision
  const ExerciseSettings exercise = discharge();
  const Attempt a = drive(exercise, {.travel_below_the_coaming = true}, 200.0);
  EXPECT_GT(a.metrics.ship_collisions, 0);
  std::printf("travelling below the coaming: %d ship collisions\n", a.metrics.ship_collisions);
  EXPECT_GE(deducted(a.score, "collision"), exercise.rules.points_collision * a.metrics.ship_collisions);
}

TEST(MhcDischarge, AnInstructorTakeOverWithTheGrabLoadedFinishesTheDelivery) {
  // the original attempt recorded to 125 s (the second bite hoisting out of the hold); taken over there, the
  // scripted operator the factory picks for the exercise resumes with the loaded grab and clears it
  const ExerciseSettings exercise = discharge();
  constexpr std::int64_t kAt = 125000;
  Recorder recorder(exercise.name, Simulation(exercise.scenario).control_table());
  {
    Simulation sim(exercise.scenario);
    const std::unique_ptr<Pilot> pilot = make_pilot(exercise);
    for (std::int64_t k = 0; k < kAt; ++k) {
      const scene::Controls in = pilot->next(sim);
      sim.step(in);
      recorder.after_step(sim, in);
    }
  }
  Evaluator evaluator(exercise);
  TakeOver branch =
      take_over(exercise.scenario, recorder.recording(), "original", kAt,
                [&](const Simulation& s, const scene::Controls& in) { evaluator.observe(s, in); });
  const Simulation& at = *branch.simulation;
  ASSERT_GT(at.bulk()->grab(at.bulk_grab()).load_m3,
            0.5 * at.bulk()->grab_settings(at.bulk_grab()).capacity_m3);
  const double delivered_before = evaluator.metrics().delivered_t;
  EXPECT_GT(delivered_before, 0.0);
  const std::unique_ptr<Pilot> pilot = make_pilot(exercise);
  pilot->resume(at, evaluator.metrics().moves_completed, branch.levers);
  while (!evaluator.finished() && branch.simulation->time_s() < limit_of(exercise)) {
    const scene::Controls in = pilot->next(*branch.simulation);
    branch.simulation->step(in);
    evaluator.observe(*branch.simulation, in);
  }
  EXPECT_TRUE(evaluator.finished());
  EXPECT_TRUE(evaluator.score().passed);
  EXPECT_EQ(evaluator.metrics().overloads, 0);
  for (const double fill : evaluator.metrics().bite_fill)  // it digs where the material stands highest
    EXPECT_GT(fill, 0.8);
  std::printf("taken over at 125 s: finished at %.1f s, score %.0f\n", evaluator.metrics().time_s,
              evaluator.score().total);
}

TEST(MhcDischarge, SlammingTheSlewLeverIsHarshAndSteadyDrivingIsNot) {
  // the same 60 s of slewing: the lever slammed from full one way to full the other every 4 s, and the lever
  // held at half: the slam's jerk at the boom head shows in the RMS and counts harsh moves, steady driving
  // not
  const ExerciseSettings exercise = discharge();
  const auto slew_smoothness = [&](bool slam) {
    Simulation sim(exercise.scenario);
    Evaluator evaluator(exercise);
    scene::Controls c = sim.control_table().neutral();
    const std::size_t slew = static_cast<std::size_t>(sim.control_table().find("slew"));
    for (int k = 0; k < 60000; ++k) {
      c.value[slew] = slam ? ((k / 4000) % 2 == 0 ? 1.0 : -1.0) : (k < 30000 ? 0.5 : 0.0);
      sim.step(c);
      evaluator.observe(sim, c);
    }
    EXPECT_EQ(evaluator.metrics().smoothness.size(), 2u);
    return evaluator.metrics().smoothness.at(0);
  };
  const Metrics::Smoothness slammed = slew_smoothness(true), steady = slew_smoothness(false);
  EXPECT_EQ(slammed.axis, "slew");
  EXPECT_GT(slammed.harsh_moves, 5);
  EXPECT_EQ(steady.harsh_moves, 0);
  EXPECT_GT(slammed.rms_jerk_mps3, 3.0 * steady.rms_jerk_mps3);
}

TEST(MhcDischarge, TheHoldMovesWithTheVessel) {
  ExerciseSettings exercise = discharge();
  exercise.scenario.vessel->sea.heave_m.push_back({0.4, 8.0, 0.0});
  Simulation sim(exercise.scenario);
  const scene::Controls neutral = sim.control_table().neutral();
  for (int k = 0; k < 2000; ++k)  // a quarter of the heave period: the vessel at its crest
    sim.step(neutral);
  const VesselGeometry geometry(*exercise.scenario.vessel);
  const core::Pose vessel = geometry.pose_at(sim.time_s());
  const bulk::GridPlacement& hold = exercise.scenario.bulk->grids[0];
  const core::Vec3 corner = vessel.to_parent({hold.origin_x_m, hold.origin_y_m, hold.origin_z_m});
  const core::Vec3 grid = sim.bulk()->grid(0).pose().position;
  EXPECT_NEAR(grid.z - hold.origin_z_m - exercise.scenario.vessel->keel_midship_m.z, 0.4, 0.01);
  EXPECT_NEAR(std::hypot(grid.x - corner.x, grid.y - corner.y, grid.z - corner.z), 0.0, 1e-5);
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

ExerciseSettings pile_trim() {
  return io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_pile_trim.yaml");
}

TEST(MhcPileTrim, TheAutopilotTakesThePilesTopDownAndKeepsItsMaterialOnTheStockpile) {
  // dig where the pile stands highest, drop the bite where the stockpile lies lowest, again until its top is
  // down to the goal: the material stays on the stockpile, the volume balance exact
  const ExerciseSettings exercise = pile_trim();
  const Simulation start(exercise.scenario);
  const double top_at_start = pile_top_m(*start.bulk(), exercise.trim->grid_index);
  EXPECT_GT(top_at_start, exercise.trim->top_m + 2.0);
  const Attempt a = drive(exercise, {}, limit_of(exercise));
  ASSERT_TRUE(a.finished);
  EXPECT_TRUE(a.metrics.trim);
  EXPECT_LE(a.metrics.pile_top_m, exercise.trim->top_m);
  EXPECT_LE(a.metrics.time_s, exercise.rules.time_limit_s);
  EXPECT_GE(a.metrics.bite_fill.size(), 3u);
  EXPECT_EQ(a.metrics.spilled_t, 0.0);
  EXPECT_NEAR(a.back_in_hold_t, a.metrics.handled_t, 1e-9 * a.metrics.handled_t);  // all landed on the pile
  EXPECT_LT(a.worst_discrepancy_m3, 1e-9 * a.added_m3);
  EXPECT_EQ(a.metrics.overloads, 0);
  EXPECT_EQ(a.metrics.limiter_trips, 0);
  EXPECT_EQ(a.metrics.pad_lift_offs, 0);
  EXPECT_TRUE(a.score.passed);
  EXPECT_EQ(deducted(a.score, "decimetre above the trim height"), 0.0);
  std::printf("trim: %.2f m -> %.2f m in %.0f s, %zu bites, %.1f t moved, score %.0f\n", top_at_start,
              a.metrics.pile_top_m, a.metrics.time_s, a.metrics.bite_fill.size(), a.metrics.handled_t,
              a.score.total);
}

TEST(MhcPileTrim, StoppingWithThePileStillHighCostsPerDecimetre) {
  // one bite in a minute: the top is still above the goal, each decimetre over it deducted
  const ExerciseSettings exercise = pile_trim();
  const Attempt a = drive(exercise, {}, 60.0);
  EXPECT_FALSE(a.finished);
  ASSERT_GT(a.metrics.pile_top_m, exercise.trim->top_m);
  EXPECT_NEAR(deducted(a.score, "decimetre above the trim height"),
              std::ceil((a.metrics.pile_top_m - exercise.trim->top_m) * 10.0 - 1e-9) *
                  exercise.rules.points_per_trim_dm,
              1e-9);
  EXPECT_FALSE(a.score.passed);
}

}  // namespace
}  // namespace harbour::sim
