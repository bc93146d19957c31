#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"

namespace harbour::sim {
namespace {

constexpr double kG = 9.80665;

ExerciseSettings free_practice() {
  return io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_free_practice.yaml");
}

const TerminalTractor& tractor(const Simulation& sim) {
  return dynamic_cast<const TerminalTractor&>(sim.machine());
}

// the cab's controls: a throttle holding `speed_mps` (brake above it) in `direction`, the wheel at `steer`
Controls driving(const Simulation& sim, double speed_mps, double steer, const char* direction = "forward") {
  const ControlTable& table = sim.control_table();
  Controls c = table.neutral();
  const double error = speed_mps - std::abs(tractor(sim).forward_mps());
  c.value[static_cast<std::size_t>(table.find("throttle"))] = std::clamp(0.5 * error, 0.0, 1.0);
  c.value[static_cast<std::size_t>(table.find("brake"))] = std::clamp(-0.5 * error, 0.0, 1.0);
  c.value[static_cast<std::size_t>(table.find("steer"))] = steer;
  const std::vector<std::string>& positions = table[table.find("direction")].positions;
  c.value[static_cast<std::size_t>(table.find("direction"))] =
      static_cast<double>(std::find(positions.begin(), positions.end(), direction) - positions.begin());
  return c;
}

void drive(Simulation& sim, double seconds, double speed_mps, double steer,
           const char* direction = "forward") {
  for (int k = 0; k < static_cast<int>(std::lround(seconds / Simulation::kStep_s)); ++k)
    sim.step(driving(sim, speed_mps, steer, direction));
  ASSERT_FALSE(sim.diverged()) << sim.divergence();
}

TEST(Tractor, AtFullLockItTurnsOnTheAckermannCircle) {
  // the shipped tractor at walking pace, the wheel at full lock: the rear axle's centre turns at L / tan δ
  Simulation sim(free_practice().scenario);
  drive(sim, 25.0, 1.5, 1.0);
  const TerminalTractor& t = tractor(sim);
  const WheeledChassisSettings& c = t.settings().chassis;
  const double wheelbase = c.axles[0].x_m - c.axles[1].x_m;
  const double expected = wheelbase / std::tan(c.max_steer_rad);
  const core::Vec3 rear = sim.world().point_velocity(t.body(), {c.axles[1].x_m, 0, 0});
  const double radius = std::hypot(rear.x, rear.y) / std::abs(sim.world().angular_velocity(t.body()).z);
  EXPECT_NEAR(radius, expected, 0.05 * expected);
  EXPECT_NEAR(t.steering(), 1.0, 1e-12);
  std::printf("tractor at full lock: %.3f m against L / tan(delta) = %.3f m\n", radius, expected);
}

TEST(Tractor, FullBrakesStopItInTheDistanceItsGripAndBrakesAllow) {
  // braking moves load onto the front axle (m a h / L): the unloaded rear wheels lock and slide at µ·Fz, the
  // loaded front wheels' grip exceeds their brakes and they hold the brake torque / r; the deceleration
  // solves a = (F_front(a) + F_rear(a)) / m, the stop v² / (2a)
  Simulation sim(free_practice().scenario);
  drive(sim, 15.0, 6.0, 0.0);
  const TerminalTractor& t = tractor(sim);
  const double v = t.forward_mps();
  ASSERT_GT(v, 5.0);
  const core::Vec3 from = sim.world().pose(t.body()).position;
  const WheeledChassisSettings& c = t.settings().chassis;
  const double m = t.settings().mass_kg, mu = c.tyre.friction, h = from.z;
  const double front = c.axles[0].x_m, rear = -c.axles[1].x_m, wheelbase = front + rear;
  double a = 0.0;
  for (int k = 0; k < 100; ++k) {
    const double shift = m * a * h / wheelbase;
    const double on_front = m * kG * rear / wheelbase + shift, on_rear = m * kG * front / wheelbase - shift;
    const double braking_front = std::min(2 * c.brake_torque_per_wheel_nm / c.tyre.radius_m, mu * on_front);
    const double braking_rear =
        std::min(2 * c.axles[1].tyres_per_side * c.brake_torque_per_wheel_nm / c.tyre.radius_m, mu * on_rear);
    a = (braking_front + braking_rear) / m;
  }
  Controls brake = sim.control_table().neutral();
  brake.value[static_cast<std::size_t>(sim.control_table().find("brake"))] = 1.0;
  for (int k = 0; k < 10000 && t.forward_mps() > 0.01; ++k)
    sim.step(brake);
  const core::Vec3 to = sim.world().pose(t.body()).position;
  const double expected = v * v / (2 * a);
  EXPECT_LT(a, mu * kG);  // the front brakes, not the grip, limit it
  EXPECT_NEAR(std::hypot(to.x - from.x, to.y - from.y), expected, 0.05 * expected);
  std::printf(
      "tractor braking from %.2f m/s: %.3f m against %.3f m (a = %.2f m/s^2; sliding all round: %.3f m)\n", v,
      std::hypot(to.x - from.x, to.y - from.y), expected, a, v * v / (2 * mu * kG));
}

TEST(Tractor, NeutralDoesNotDriveAndReverseDrivesBackwards) {
  Simulation sim(free_practice().scenario);
  drive(sim, 5.0, 3.0, 0.0, "neutral");
  EXPECT_LT(std::abs(tractor(sim).forward_mps()), 0.01);
  drive(sim, 10.0, 2.0, 0.0, "reverse");
  EXPECT_NEAR(tractor(sim).forward_mps(), -2.0, 0.3);
}

TEST(Tractor, StepsAreAPureFunctionOfTheInputsAndKeyframesContinueBitForBit) {
  const ExerciseSettings exercise = free_practice();
  Simulation a(exercise.scenario), b(exercise.scenario);
  drive(a, 8.0, 4.0, 0.4);
  drive(b, 8.0, 4.0, 0.4);
  EXPECT_EQ(a.state_hash(), b.state_hash());
  const std::vector<std::uint8_t> keyframe = a.save_state();
  drive(a, 5.0, 4.0, -0.7);
  Simulation restored(exercise.scenario);
  restored.restore_state(keyframe);
  drive(restored, 5.0, 4.0, -0.7);
  EXPECT_EQ(restored.state_hash(), a.state_hash());
}

TEST(Tractor, ItsDrivingIsEvaluatedForHarshBraking) {
  // slamming the brakes from speed is a harsh move on its drive; the free practice has no goals
  const ExerciseSettings exercise = free_practice();
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  for (int k = 0; k < 20000; ++k) {
    Controls c = driving(sim, 6.0, 0.0);
    if (k >= 15000) {
      c = sim.control_table().neutral();
      c.value[static_cast<std::size_t>(sim.control_table().find("brake"))] = 1.0;
    }
    sim.step(c);
    evaluator.observe(sim, c);
  }
  ASSERT_EQ(evaluator.metrics().smoothness.size(), 1u);
  EXPECT_EQ(evaluator.metrics().smoothness[0].axis, "drive");
  EXPECT_GE(evaluator.metrics().smoothness[0].harsh_moves, 1);
  EXPECT_FALSE(evaluator.finished());
}

// The free practice's tractor with a 40 ft mafi (18 t with its load) coupled over its rear axle: the
// trailer's single axle 10.1 m behind the kingpin, its tyres carrying it level.
ScenarioSettings with_a_mafi() {
  ScenarioSettings s = free_practice().scenario;
  TractorSetup& setup = std::get<TractorSetup>(s.machine);
  TrailerSettings mafi;
  mafi.mass_kg = 18000.0;
  mafi.kingpin_m = {5.6, 0.0, 0.3};
  mafi.wheels.tyre = setup.vehicle.chassis.tyre;
  mafi.wheels.tyre.radius_m = 0.4;
  const double centre_z = setup.vehicle.chassis.tyre.radius_m - setup.vehicle.chassis.axles[0].hub_z_m +
                          setup.vehicle.hitch_m.z - mafi.kingpin_m.z;
  mafi.wheels.axles = {{-4.5, 1.0, -(centre_z - mafi.wheels.tyre.radius_m), false, false, 2}};
  mafi.wheels.brake_torque_per_wheel_nm = setup.vehicle.chassis.brake_torque_per_wheel_nm;
  setup.start.trailer = mafi;
  return s;
}

TEST(Tractor, ATrailerOffTracksOnASteadyTurnByTheKinematicModel) {
  // the hitch over the tractor's rear axle turning at R1: the trailer's axle, L2 behind the hitch, runs on
  // the circle sqrt(R1² − L2²) inside it
  Simulation sim(with_a_mafi());
  const TerminalTractor& t = tractor(sim);
  ASSERT_NE(t.trailer_body(), physics::kWorld);
  const WheeledChassisSettings& c = t.settings().chassis;
  const double wheelbase = c.axles[0].x_m - c.axles[1].x_m, r1 = 15.0;
  const double steer = std::atan(wheelbase / r1) / c.max_steer_rad;
  drive(sim, 80.0, 1.5, steer);
  const auto radius_at = [&](physics::BodyId body, const core::Vec3& point) {
    const core::Vec3 v = sim.world().point_velocity(body, point);
    return std::hypot(v.x, v.y) / std::abs(sim.world().angular_velocity(body).z);
  };
  const double tractor_r = radius_at(t.body(), {c.axles[1].x_m, 0, 0});
  const double l2 = 5.6 - (-4.5);
  const double expected = std::sqrt(tractor_r * tractor_r - l2 * l2);
  const double trailer_r = radius_at(t.trailer_body(), {-4.5, 0, 0});
  EXPECT_NEAR(tractor_r, r1, 0.05 * r1);
  EXPECT_NEAR(trailer_r, expected, 0.05 * expected);
  EXPECT_EQ(t.jackknifes(), 0u);
  std::printf(
      "mafi on a %.2f m turn: its axle on %.2f m against sqrt(R1^2 - L2^2) = %.2f m, hitch %.1f deg\n",
      tractor_r, trailer_r, expected, t.hitch_angle_rad() * 180.0 / std::numbers::pi);
}

TEST(Tractor, ReversingWithTheWheelTurnedFoldsTheTrailerIntoAJackknife) {
  // backing a trailer is unstable: held steering folds it until the hitch angle passes the set limit, once
  Simulation sim(with_a_mafi());
  drive(sim, 5.0, 1.0, 0.0);
  EXPECT_EQ(tractor(sim).jackknifes(), 0u);
  drive(sim, 40.0, 1.0, 0.6, "reverse");
  EXPECT_EQ(tractor(sim).jackknifes(), 1u);
  EXPECT_GT(std::abs(tractor(sim).hitch_angle_rad()), tractor(sim).settings().jackknife_angle_rad);
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

ExerciseSettings mafi_park() {
  return io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_mafi_park.yaml");
}

// `controls` with the couple button held (or not)
Controls coupling(const Simulation& sim, Controls c, bool pressed) {
  c.value[static_cast<std::size_t>(sim.control_table().find("couple"))] = pressed ? 1.0 : 0.0;
  return c;
}

void hold(Simulation& sim, double seconds, const Controls& c) {
  for (int k = 0; k < static_cast<int>(std::lround(seconds / Simulation::kStep_s)); ++k)
    sim.step(c);
}

TEST(Tractor, ItDropsATrailerOnlyAtAStandstillAndCouplesItAgainFromBelow) {
  Simulation sim(mafi_park().scenario);
  const TerminalTractor& t = tractor(sim);
  ASSERT_TRUE(t.coupled());
  EXPECT_EQ(t.held_item(), t.trailer_body());
  // settled at the start: the combination stands still on its springs
  hold(sim, 1.0, driving(sim, 0.0, 0.0));
  EXPECT_LT(std::abs(t.forward_mps()), 0.01);
  EXPECT_LT(core::length(t.jaw_m() - t.kingpin_m()), 0.03);

  // moving: the button does nothing
  drive(sim, 6.0, 2.0, 0.0);
  hold(sim, 0.1, coupling(sim, driving(sim, 2.0, 0.0), true));
  hold(sim, 4.0, driving(sim, 2.0, 0.0));
  EXPECT_TRUE(t.coupled());
  EXPECT_DOUBLE_EQ(t.lift(), 1.0);

  // standing: the plate lowers the front onto its legs, then the jaw opens
  drive(sim, 5.0, 0.0, 0.0);
  const double kingpin_up = t.kingpin_m().z;
  hold(sim, 0.1, coupling(sim, driving(sim, 0.0, 0.0), true));
  hold(sim, 4.0, driving(sim, 0.0, 0.0));
  EXPECT_FALSE(t.coupled());
  EXPECT_FALSE(t.held_item());
  EXPECT_DOUBLE_EQ(t.lift(), 0.0);
  const double kingpin_down = t.kingpin_m().z;
  EXPECT_LT(kingpin_down, kingpin_up - 0.05);   // resting on its legs (about 0.1 m clear while lifted)
  EXPECT_LT(t.jaw_m().z, kingpin_down - 0.15);  // and the plate came 0.3 m down, off it

  // driving away leaves it standing where it is
  const core::Vec3 dropped = sim.world().pose(t.trailer_body()).position;
  drive(sim, 8.0, 1.5, 0.0);
  drive(sim, 4.0, 0.0, 0.0);
  EXPECT_LT(core::length(sim.world().pose(t.trailer_body()).position - dropped), 0.02);
  EXPECT_GT(core::length(t.jaw_m() - t.kingpin_m()), 5.0);
  // out of reach: the button does nothing
  hold(sim, 0.1, coupling(sim, driving(sim, 0.0, 0.0), true));
  hold(sim, 0.5, driving(sim, 0.0, 0.0));
  EXPECT_FALSE(t.coupled());

  // backed under it until the jaw is within reach, it couples and lifts the front off the legs
  for (int k = 0; k < 60000 && std::hypot(t.jaw_m().x - t.kingpin_m().x, t.jaw_m().y - t.kingpin_m().y) > 0.1;
       ++k)
    sim.step(driving(sim, 0.5, 0.0, "reverse"));
  drive(sim, 3.0, 0.0, 0.0, "reverse");
  hold(sim, 0.1, coupling(sim, driving(sim, 0.0, 0.0), true));
  hold(sim, 5.0, driving(sim, 0.0, 0.0));
  EXPECT_TRUE(t.coupled());
  EXPECT_DOUBLE_EQ(t.lift(), 1.0);
  EXPECT_NEAR(t.kingpin_m().z, kingpin_up, 0.02);
  EXPECT_LT(std::hypot(t.jaw_m().x - t.kingpin_m().x, t.jaw_m().y - t.kingpin_m().y), 0.01);
  // and it tows it away
  const core::Vec3 before = sim.world().pose(t.trailer_body()).position;
  drive(sim, 8.0, 2.0, 0.0);
  EXPECT_GT(core::length(sim.world().pose(t.trailer_body()).position - before), 5.0);
  EXPECT_FALSE(sim.diverged());
}

struct ParkRun {
  Metrics metrics;
  Score score;
};

// The park exercise under a pilot's controls, `adjust` changing them (a bad driver), to its end.
template <typename Adjust>
ParkRun run_park(Adjust adjust) {
  const ExerciseSettings exercise = mafi_park();
  Simulation sim(exercise.scenario);
  const std::unique_ptr<Pilot> pilot = make_pilot(exercise);
  Evaluator evaluator(exercise);
  while (!evaluator.finished() && sim.time_s() < exercise.rules.time_limit_s) {
    const Controls c = adjust(sim, pilot->next(sim));
    sim.step(c);
    evaluator.observe(sim, c);
  }
  return {evaluator.metrics(), evaluator.score()};
}

TEST(TractorPark, TheAutopilotParksTheMafiSquareOnItsMark) {
  const ParkRun run = run_park([](const Simulation&, const Controls& c) { return c; });
  EXPECT_EQ(run.metrics.moves_completed, 1);
  ASSERT_EQ(run.metrics.placement_offset_m.size(), 1u);
  EXPECT_LT(run.metrics.placement_offset_m[0], 0.3);
  ASSERT_EQ(run.metrics.placement_skew_deg.size(), 1u);
  EXPECT_LT(run.metrics.placement_skew_deg[0], 1.5);
  EXPECT_EQ(run.metrics.jackknifes, 0);
  EXPECT_EQ(run.metrics.overspeeds, 0);
  EXPECT_EQ(run.metrics.collisions, 0);
  EXPECT_TRUE(run.score.passed);
  EXPECT_GE(run.score.total, 95.0);
  std::printf("mafi parked in %.1f s, %.2f m off its mark, %.2f deg skew, score %.0f\n", run.metrics.time_s,
              run.metrics.placement_offset_m[0], run.metrics.placement_skew_deg[0], run.score.total);
}

TEST(TractorPark, SpeedingIntoTheLanesAndStoppingShortArePenalised) {
  // a driver who keeps his foot down into the marshalling lanes (10 km/h) and brakes late, short of the mark
  const ParkRun run = run_park([](const Simulation& sim, Controls c) {
    const ControlTable& table = sim.control_table();
    const core::Vec3 p = sim.world().pose(sim.machine().cab_body()).position;
    if (p.x < -20.0 && p.x > -40.0 && p.y > 10.0) {
      c.value[static_cast<std::size_t>(table.find("throttle"))] = 1.0;
      c.value[static_cast<std::size_t>(table.find("brake"))] = 0.0;
    } else if (p.x <= -40.0) {
      c.value[static_cast<std::size_t>(table.find("throttle"))] = 0.0;
      c.value[static_cast<std::size_t>(table.find("brake"))] = 1.0;
    }
    return c;
  });
  EXPECT_GE(run.metrics.overspeeds, 1);
  EXPECT_GT(run.metrics.worst_overspeed_kmh, 1.0);
  EXPECT_EQ(run.metrics.moves_completed, 0);  // dropped far from the mark, or never
  EXPECT_FALSE(run.score.passed);
  const auto has = [&](const std::string& reason) {
    return std::any_of(run.score.deductions.begin(), run.score.deductions.end(),
                       [&](const Score::Deduction& d) { return d.reason == reason; });
  };
  EXPECT_TRUE(has("speeding"));
  EXPECT_TRUE(has("move not completed"));
  EXPECT_TRUE(has("harsh move"));  // the slammed brake
  std::printf("the bad driver: %d speeding (worst %.1f km/h over), score %.0f\n", run.metrics.overspeeds,
              run.metrics.worst_overspeed_kmh, run.score.total);
}

TEST(TractorPark, KeyframesMidDropContinueBitForBit) {
  const ExerciseSettings exercise = mafi_park();
  Simulation sim(exercise.scenario);
  const std::unique_ptr<Pilot> pilot = make_pilot(exercise);
  while (std::string(pilot->activity()) != "drop" && sim.time_s() < 120.0)
    sim.step(pilot->next(sim));
  ASSERT_EQ(std::string(pilot->activity()), "drop");
  for (int k = 0; k < 1000; ++k)  // the plate on its way down
    sim.step(pilot->next(sim));
  ASSERT_TRUE(tractor(sim).coupled());
  ASSERT_GT(tractor(sim).lift(), 0.0);
  ASSERT_LT(tractor(sim).lift(), 1.0);
  const std::vector<std::uint8_t> keyframe = sim.save_state();
  std::vector<Controls> inputs;
  for (int k = 0; k < 4000; ++k) {
    inputs.push_back(pilot->next(sim));
    sim.step(inputs.back());
  }
  EXPECT_FALSE(tractor(sim).coupled());
  Simulation again(exercise.scenario);
  again.restore_state(keyframe);
  for (const Controls& c : inputs)
    again.step(c);
  EXPECT_EQ(again.state_hash(), sim.state_hash());
}

}  // namespace
}  // namespace harbour::sim
