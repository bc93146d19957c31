#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/tractor/Files.h"
#include "harbour/machines/tractor/TractorAutopilot.h"
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
scene::Controls driving(const Simulation& sim, double speed_mps, double steer,
                        const char* direction = "forward") {
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = table.neutral();
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

// Its travel energy is what its drive delivers at the tyres' contacts: brought up to 5 m/s on the level in
// still air, the body's kinetic energy plus the work of rolling resistance, Crr m g over the distance, and of
// the air's drag on its box, 1/2 rho Cd A v^3 over the time (A its frontal area); cruising on, the last two.
TEST(Tractor, ItsDriveDeliversTheKineticEnergyAndTheWorkOfRollingResistanceAndDrag) {
  const ExerciseSettings exercise = free_practice();
  Simulation sim(exercise.scenario);
  const TerminalTractor& t = tractor(sim);
  const double mass = sim.world().mass_kg(t.body());
  const double frontal_m2 = 4.0 * t.settings().half_extents_m.y * t.settings().half_extents_m.z;
  const double drag_factor =
      0.5 * exercise.scenario.weather.air_density_kg_m3 * exercise.scenario.drag_coefficient * frontal_m2;
  struct Leg {
    double delivered_j = 0.0, drag_j = 0.0, distance_m = 0.0, kinetic_gain_j = 0.0;
  };
  auto drive_on = [&](double seconds) {
    Leg leg;
    const core::Vec3 from = sim.world().pose(t.body()).position;
    const core::Vec3 v0 = sim.world().linear_velocity(t.body());
    for (int k = 0; k < static_cast<int>(std::lround(seconds / Simulation::kStep_s)); ++k) {
      const double speed = core::length(sim.world().linear_velocity(t.body()));
      sim.step(driving(sim, 5.0, 0.0));
      leg.delivered_j += sim.machine().tally().travel_power_w * Simulation::kStep_s;
      leg.drag_j += drag_factor * speed * speed * speed * Simulation::kStep_s;
    }
    const core::Vec3 to = sim.world().pose(t.body()).position;
    const core::Vec3 v1 = sim.world().linear_velocity(t.body());
    leg.distance_m = std::hypot(to.x - from.x, to.y - from.y);
    leg.kinetic_gain_j = 0.5 * mass * (dot(v1, v1) - dot(v0, v0));
    return leg;
  };
  const double crr = t.settings().chassis.tyre.rolling_resistance;
  for (const double seconds : {15.0, 10.0}) {  // brought up to speed, then cruising
    const Leg leg = drive_on(seconds);
    const double rolling_j = crr * mass * kG * leg.distance_m;
    const double expected = leg.kinetic_gain_j + rolling_j + leg.drag_j;
    std::printf("%.0f s: drive delivered %.0f J against kinetic %.0f + rolling %.0f + drag %.0f = %.0f J\n",
                seconds, leg.delivered_j, leg.kinetic_gain_j, rolling_j, leg.drag_j, expected);
    EXPECT_NEAR(leg.delivered_j, expected, 0.01 * expected);
  }
  EXPECT_GT(core::length(sim.world().linear_velocity(t.body())), 4.5);
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
  scene::Controls brake = sim.control_table().neutral();
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
    scene::Controls c = driving(sim, 6.0, 0.0);
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
  TractorSetup& setup = s.machine.as<TractorSetup>();
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
scene::Controls coupling(const Simulation& sim, scene::Controls c, bool pressed) {
  c.value[static_cast<std::size_t>(sim.control_table().find("couple"))] = pressed ? 1.0 : 0.0;
  return c;
}

void hold(Simulation& sim, double seconds, const scene::Controls& c) {
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
    const scene::Controls c = adjust(sim, pilot->next(sim));
    sim.step(c);
    evaluator.observe(sim, c);
  }
  return {evaluator.metrics(), evaluator.score()};
}

TEST(TractorPark, TheAutopilotParksTheMafiSquareOnItsMark) {
  const ParkRun run = run_park([](const Simulation&, const scene::Controls& c) { return c; });
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
  const ParkRun run = run_park([](const Simulation& sim, scene::Controls c) {
    const scene::ControlTable& table = sim.control_table();
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
  std::vector<scene::Controls> inputs;
  for (int k = 0; k < 4000; ++k) {
    inputs.push_back(pilot->next(sim));
    sim.step(inputs.back());
  }
  EXPECT_FALSE(tractor(sim).coupled());
  Simulation again(exercise.scenario);
  again.restore_state(keyframe);
  for (const scene::Controls& c : inputs)
    again.step(c);
  EXPECT_EQ(again.state_hash(), sim.state_hash());
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

// The free practice's tractor 40 m before a long stern ramp rising 3.6 m over 36 m (1:10) up the +y axis,
// wet (its grip half the quay's), towing the shipped 40 ft mafi with `payload_kg` over its axle (little of it
// on the kingpin, so little on the drive axle).
ScenarioSettings before_a_wet_ramp(double payload_kg) {
  ScenarioSettings s = free_practice().scenario;
  TractorSetup& setup = s.machine.as<TractorSetup>();
  setup.start.position_m = {0.0, -40.0, 0.0};
  setup.start.heading_rad = std::numbers::pi / 2;
  TrailerSettings mafi = io::load_trailer(HARBOUR_DATA_DIR "/trailers/mafi_40ft.yaml");
  const double axle_x = mafi.wheels.axles.front().x_m;
  mafi.center_of_mass_x_m = payload_kg * axle_x / (mafi.mass_kg + payload_kg);
  mafi.mass_kg += payload_kg;
  setup.start.trailer = mafi;
  RampSettings ramp;
  ramp.toe_m = {0.0, 0.0, 0.0};
  ramp.heading_rad = std::numbers::pi / 2;
  ramp.length_m = 36.0;
  ramp.deck_height_m = 3.6;
  ramp.grip = 0.5;
  s.ramp = ramp;
  return s;
}

// The drive axle's grip left over when the combination climbs the ramp steadily [N] (< 0: it cannot): the
// statics of both bodies on the slope, with the load each axle gains or loses from the drawbar pull at the
// hitch's height and the weights' components along the slope at their centres' heights; the drive tyres push
// µ·N_rear along the ramp at most.
double traction_margin_n(const ScenarioSettings& s) {
  const TractorSetup& setup = s.machine.as<TractorSetup>();
  const TractorSettings& v = setup.vehicle;
  const WheeledChassisSettings& c = v.chassis;
  const TrailerSettings& t = *setup.start.trailer;
  const double slope = std::atan2(s.ramp->deck_height_m, s.ramp->length_m);
  const double sn = std::sin(slope), cs = std::cos(slope), crr = c.tyre.rolling_resistance;
  const double mu = c.tyre.friction * s.ramp->grip;
  // heights over the ground: the tractor's centre of mass and hitch, the mafi's centre and kingpin
  const double tractor_h = c.tyre.radius_m - c.axles[0].hub_z_m, hitch_h = tractor_h + v.hitch_m.z;
  const double trailer_h = t.wheels.tyre.radius_m - t.wheels.axles.front().hub_z_m;
  const double axle_x = t.wheels.axles.front().x_m, front_x = c.axles[0].x_m, rear_x = c.axles[1].x_m;
  const double mt = t.mass_kg * kG, mT = v.mass_kg * kG;
  // the mafi: pulled by P along the ramp at the kingpin, carried by K there and by its axle
  double pull = 0.0, kingpin = 0.0;
  for (int pass = 0; pass < 20; ++pass) {  // P depends on the axle's rolling resistance, its load on K
    kingpin = ((t.center_of_mass_x_m - axle_x) * mt * cs - trailer_h * mt * sn + hitch_h * pull) /
              (t.kingpin_m.x - axle_x);
    pull = mt * sn + crr * (mt * cs - kingpin);
  }
  // the tractor: moments about its rear axle's contact (the hitch straight over it)
  const double front_n = (-rear_x * mT * cs - tractor_h * mT * sn - hitch_h * pull) / (front_x - rear_x);
  const double rear_n = mT * cs + kingpin - front_n;
  return mu * rear_n - (pull + mT * sn + crr * front_n);
}

// The payload over the mafi's axle at which the grip just holds the climb (bisection on the margin).
double limit_payload_kg() {
  double low = 0.0, high = 60000.0;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (low + high);
    (traction_margin_n(before_a_wet_ramp(mid)) > 0.0 ? low : high) = mid;
  }
  return low;
}

struct Climb {
  bool on_deck = false;    // the mafi's centre reached the deck
  double climbed_m = 0.0;  // the tractor's rise after the hill start
};

// Up the ramp at walking pace until the whole combination is on it, a stop, then a hill start at full
// throttle for 60 s.
Climb hill_start(double payload_kg) {
  Simulation sim(before_a_wet_ramp(payload_kg));
  const TerminalTractor& t = tractor(sim);
  const auto trailer_axle_y = [&] {
    return sim.world().pose(t.trailer_body()).to_parent({-4.5, 0.0, 0.0}).y;
  };
  for (int k = 0; k < 120000 && trailer_axle_y() < 2.0; ++k)
    sim.step(driving(sim, 1.0, 0.0));
  drive(sim, 3.0, 0.0, 0.0);
  const double start_z = sim.world().pose(t.body()).position.z;
  Climb result;
  scene::Controls c = driving(sim, 0.0, 0.0);
  c.value[static_cast<std::size_t>(sim.control_table().find("throttle"))] = 1.0;
  c.value[static_cast<std::size_t>(sim.control_table().find("brake"))] = 0.0;
  for (int k = 0; k < 60000 && !result.on_deck; ++k) {
    sim.step(c);
    result.on_deck = sim.world().pose(t.trailer_body()).position.y > 36.0 + 6.1;
  }
  result.climbed_m = sim.world().pose(t.body()).position.z - start_z;
  EXPECT_FALSE(sim.diverged());
  return result;
}

TEST(TractorRamp, TheClimbFailsWhenTheLoadExceedsWhatTheDriveAxlesGripCanPull) {
  const double limit_kg = limit_payload_kg();
  ASSERT_GT(limit_kg, 5000.0);
  ASSERT_LT(limit_kg, 40000.0);
  // the engine (its converter at stall) could pull more: the grip decides
  const TractorSettings vehicle = free_practice().scenario.machine.as<TractorSetup>().vehicle;
  const double stall_pull_n =
      drivetrain_wheel_torque_nm(vehicle.chassis.drivetrain, vehicle.chassis.tyre.radius_m, 1.0, 0.0).first /
      vehicle.chassis.tyre.radius_m;
  const double slope = std::atan2(3.6, 36.0);
  ASSERT_GT(stall_pull_n,
            (8000.0 + 8500.0 + 1.2 * limit_kg) * kG * (std::sin(slope) + 0.012 * std::cos(slope)));

  const Climb light = hill_start(0.8 * limit_kg);
  EXPECT_TRUE(light.on_deck);
  const Climb heavy = hill_start(1.2 * limit_kg);
  EXPECT_FALSE(heavy.on_deck);
  EXPECT_LT(heavy.climbed_m, 0.05);  // the wheels spin where it stands (or it slides back)
  std::printf(
      "wet 1:10 ramp: the grip holds up to %.1f t over the mafi's axle; from a standstill on the ramp "
      "%.1f t climbs onto the deck, %.1f t rises %.2f m in 60 s\n",
      limit_kg / 1000.0, 0.8 * limit_kg / 1000.0, 1.2 * limit_kg / 1000.0, heavy.climbed_m);
}

// What holds the tractor on the ramp: its brake pedal, the emergency stop, or the parking brake alone.
enum class Holding { kPedal, kEmergencyStop, kParkingBrake };

// Up a dry 1:10 ramp at walking pace until the whole combination stands on it, stopped with the brake pedal
// in neutral, then held by `holding` (the pedal at `pedal`) for `seconds`: how far the tractor's centre
// travels then [m].
double travel_when_braked_on_the_ramp(double payload_kg, double pedal, double seconds, Holding holding) {
  ScenarioSettings scenario = before_a_wet_ramp(payload_kg);
  scenario.ramp->grip = 0.8;  // dry steel plates
  Simulation sim(scenario);
  const TerminalTractor& t = tractor(sim);
  // the mafi's axle 3 m up the ramp (full throttle below walking pace): the whole combination on it, the
  // mafi's rear end (1.6 m behind its axle) clear of the quay
  for (int k = 0; k < 120000 && sim.world().pose(t.trailer_body()).to_parent({-4.5, 0.0, 0.0}).y < 3.0; ++k) {
    scene::Controls c = driving(sim, 1.0, 0.0);
    if (t.forward_mps() < 1.0) c.value[static_cast<std::size_t>(sim.control_table().find("throttle"))] = 1.0;
    sim.step(c);
  }
  EXPECT_GT(sim.world().pose(t.trailer_body()).to_parent({-4.5, 0.0, 0.0}).y, 3.0)
      << "the climb stalled at " << sim.time_s() << " s, tractor y " << sim.world().pose(t.body()).position.y
      << " z " << sim.world().pose(t.body()).position.z << " speed " << t.forward_mps();
  const auto held = [&](Holding by, double amount) {
    scene::Controls c = sim.control_table().neutral();  // neutral: no drive
    const auto set = [&](const char* label, double value) {
      c.value[static_cast<std::size_t>(sim.control_table().find(label))] = value;
    };
    if (by == Holding::kPedal) set("brake", amount);
    if (by == Holding::kEmergencyStop) set("emergency_stop", 1.0);
    if (by == Holding::kParkingBrake) set("parking_brake", 1.0);
    return c;
  };
  for (int k = 0; k < 2000; ++k)  // to a stop
    sim.step(held(Holding::kPedal, 1.0));
  const core::Vec3 from = sim.world().pose(t.body()).position;
  for (int k = 0; k < static_cast<int>(std::lround(seconds / Simulation::kStep_s)); ++k)
    sim.step(held(holding, pedal));
  EXPECT_FALSE(sim.diverged()) << sim.divergence();
  const core::Vec3 to = sim.world().pose(t.body()).position;
  return std::hypot(to.x - from.x, to.y - from.y);
}

TEST(TractorBrakes, TheBrakesHoldA30TonneMafiOnA1In10RampForAMinute) {
  // static friction: braked wheels at rest stand, up to what the brakes and the grip can hold
  const double pedal = travel_when_braked_on_the_ramp(30000.0, 1.0, 60.0, Holding::kPedal);
  const double stop = travel_when_braked_on_the_ramp(30000.0, 1.0, 60.0, Holding::kEmergencyStop);
  std::printf("30 t mafi braked on 1:10 for 60 s: moved %.5f m (pedal), %.5f m (emergency stop)\n", pedal,
              stop);
  EXPECT_LT(pedal, 0.01);
  EXPECT_LT(stop, 0.01);
}

TEST(TractorBrakes, TheParkingBrakeAloneHoldsA30TonneMafiOnA1In10RampAndNothingDoesNot) {
  // the pedal released in neutral: the spring brakes on the drive axle and the mafi's brakes (applied through
  // its control line) hold it; with nothing set it rolls back down
  const double parked = travel_when_braked_on_the_ramp(30000.0, 0.0, 60.0, Holding::kParkingBrake);
  const double released = travel_when_braked_on_the_ramp(30000.0, 0.0, 3.0, Holding::kPedal);
  std::printf("30 t mafi on 1:10: moved %.5f m in 60 s on the parking brake, %.2f m in 3 s on nothing\n",
              parked, released);
  EXPECT_LT(parked, 0.01);
  EXPECT_GT(released, 1.0);
}

TEST(TractorBrakes, BrakedBelowThePullDownTheSlopeItRollsAwayAtTheDifference) {
  // the pedal eased until the brakes give half the weight's pull down the slope: the combination rolls
  // down from rest at a = g sin a - B / M - crr g cos a (B the brakes' force on every wheel together, crr by
  // weight)
  const double payload_kg = 30000.0, slope = std::atan2(3.6, 36.0);
  const ScenarioSettings scenario = before_a_wet_ramp(payload_kg);
  const TractorSetup& setup = scenario.machine.as<TractorSetup>();
  const auto full_brakes_n = [](const WheeledChassisSettings& c) {
    double n = 0.0;
    for (const AxleSettings& a : c.axles)
      n += 2.0 * a.tyres_per_side * c.brake_torque_per_wheel_nm / c.tyre.radius_m;
    return n;
  };
  const double mass_kg = setup.vehicle.mass_kg + setup.start.trailer->mass_kg;
  const double full_n = full_brakes_n(setup.vehicle.chassis) + full_brakes_n(setup.start.trailer->wheels);
  const double pedal = 0.5 * mass_kg * kG * std::sin(slope) / full_n;
  ASSERT_LT(pedal, 0.5);
  // rolling resistance by each vehicle's weight (the mafi's payload sits over its axle)
  const double crr = (setup.vehicle.chassis.tyre.rolling_resistance * setup.vehicle.mass_kg +
                      setup.start.trailer->wheels.tyre.rolling_resistance * setup.start.trailer->mass_kg) /
                     mass_kg;
  const double expected_mps2 = kG * std::sin(slope) - pedal * full_n / mass_kg - crr * kG * std::cos(slope);
  const double seconds = 3.0;  // ~1.6 m: its wheels all still on the ramp
  const double moved = travel_when_braked_on_the_ramp(payload_kg, pedal, seconds, Holding::kPedal);
  const double measured_mps2 = 2.0 * moved / (seconds * seconds);
  std::printf("brake pedal at %.3f on 1:10: rolled %.2f m in %.0f s, %.3f m/s^2 against %.3f\n", pedal, moved,
              seconds, measured_mps2, expected_mps2);
  EXPECT_NEAR(measured_mps2, expected_mps2, 0.1 * expected_mps2);
}

TEST(TractorRamp, TheDeckRisesAndFallsWithTheTideAndSwellAndTheRampWithIt) {
  RampSettings s;
  s.toe_m = {0.0, 0.0, 0.0};
  s.length_m = 18.0;
  s.deck_height_m = 1.8;
  s.tide = {1.0, 12.42 * 3600.0, 0.0};
  s.heave = {0.2, 8.0, 0.0};
  RoRoRamp ramp(s);
  ramp.move_to(2.0);  // a quarter of the swell
  const double expected = 1.8 + std::sin(2.0 * std::numbers::pi * 2.0 / (12.42 * 3600.0)) + 0.2;
  EXPECT_NEAR(ramp.deck_height_m(), expected, 1e-9);
  EXPECT_NEAR(ramp.at(9.0, 0.0).z_m, expected / 2, 1e-9);  // half way up the ramp
  EXPECT_NEAR(ramp.at(30.0, 0.0).z_m, expected, 1e-9);     // on the deck
  EXPECT_NEAR(ramp.at(30.0, 5.0).z_m, 0.0, 1e-12);         // beside the ramp: the quay
  EXPECT_NEAR(ramp.slope_rad(), std::atan2(expected, 18.0), 1e-12);
  const core::Vec3 n = ramp.at(9.0, 0.0).normal;
  EXPECT_NEAR(std::atan2(-n.x, n.z), ramp.slope_rad(), 1e-12);
  ramp.move_to(4.0);  // half the swell: the heave's speed at its most, the deck falling
  EXPECT_NEAR(ramp.at(30.0, 0.0).rise_mps,
              0.2 * 2.0 * std::numbers::pi / 8.0 * std::cos(std::numbers::pi) +
                  1.0 * 2.0 * std::numbers::pi / (12.42 * 3600.0) *
                      std::cos(2.0 * std::numbers::pi * 4.0 / (12.42 * 3600.0)),
              1e-9);
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

TEST(TractorRamp, TheAutopilotTowsTheMafiUpTheRampAndDropsItInItsDeckLane) {
  const ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_ramp_mafi.yaml");
  ASSERT_TRUE(exercise.scenario.ramp);
  Simulation sim(exercise.scenario);
  const std::unique_ptr<Pilot> pilot = make_pilot(exercise);
  Evaluator evaluator(exercise);
  std::vector<std::uint8_t> keyframe;
  std::vector<scene::Controls> after;
  std::uint64_t hash_after = 0;
  double highest_trailer_z = 0.0;
  while (!evaluator.finished() && sim.time_s() < exercise.rules.time_limit_s) {
    const scene::Controls c = pilot->next(sim);
    if (keyframe.empty() && sim.world().pose(tractor(sim).body()).position.x > 20.0)
      keyframe = sim.save_state();
    const bool recording = !keyframe.empty() && after.size() < 5000;
    if (recording) after.push_back(c);
    sim.step(c);
    if (recording && after.size() == 5000) hash_after = sim.state_hash();
    evaluator.observe(sim, c);
    highest_trailer_z = std::max(highest_trailer_z, sim.world().pose(tractor(sim).trailer_body()).position.z);
  }
  const Metrics& m = evaluator.metrics();
  EXPECT_EQ(m.moves_completed, 1);
  ASSERT_EQ(m.placement_offset_m.size(), 1u);
  EXPECT_LT(m.placement_offset_m[0], 0.3);
  EXPECT_EQ(m.overspeeds, 0);  // 5 km/h on the ramp, 10 on the deck
  EXPECT_TRUE(evaluator.score().passed);
  EXPECT_GE(evaluator.score().total, 95.0);
  // up on the deck: the mafi's centre about the deck's height (1.8 m and the tide's rise) over its level one
  EXPECT_GT(highest_trailer_z, 0.85 + 1.8);
  std::printf("mafi up the ramp and parked on the deck in %.1f s, %.2f m off its mark, score %.0f\n",
              m.time_s, m.placement_offset_m[0], evaluator.score().total);

  // its bay is painted on the deck, as high as the deck stands now
  const scene::SceneDescription scene = sim.scene();
  const auto bay = std::find_if(scene.entities.begin(), scene.entities.end(),
                                [](const auto& e) { return e.name == "bay mafi_1"; });
  ASSERT_NE(bay, scene.entities.end());
  EXPECT_EQ(bay->visual, "marking.bay");
  const auto snapshot = sim.snapshot();
  const core::Pose painted = snapshot->entities[static_cast<std::size_t>(bay - scene.entities.begin())].pose;
  EXPECT_NEAR(painted.position.x, 68.0, 1e-9);
  EXPECT_NEAR(painted.position.z,
              1.8 + 0.4 * std::sin(2.0 * std::numbers::pi * sim.time_s() / 44712.0) +
                  0.08 * std::sin(2.0 * std::numbers::pi * sim.time_s() / 9.0),
              0.02);

  // a keyframe on the ramp continues bit for bit: the deck where the clock puts it
  ASSERT_EQ(after.size(), 5000u);
  Simulation again(exercise.scenario);
  again.restore_state(keyframe);
  for (const scene::Controls& c : after)
    again.step(c);
  EXPECT_EQ(again.state_hash(), hash_after);
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

// The reversing exercise driven to its end; the largest hitch angle on the way.
struct Reversal {
  Metrics metrics;
  double score = 0.0;
  double worst_hitch_rad = 0.0;
};
Reversal reverse_into_bay(DriverDefects defects) {
  const ExerciseSettings exercise =
      io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_semi_reverse.yaml");
  Simulation sim(exercise.scenario);
  TractorAutopilot pilot(exercise, defects);
  Evaluator evaluator(exercise);
  Reversal r;
  while (!evaluator.finished() && sim.time_s() < exercise.rules.time_limit_s && !sim.diverged()) {
    const scene::Controls c = pilot.next(sim);
    sim.step(c);
    evaluator.observe(sim, c);
    r.worst_hitch_rad = std::max(r.worst_hitch_rad, std::abs(tractor(sim).hitch_angle_rad()));
  }
  EXPECT_FALSE(sim.diverged()) << sim.divergence();
  r.metrics = evaluator.metrics();
  r.score = evaluator.score().total;
  return r;
}

TEST(TractorReverse, TheAutopilotBacksTheSemiTrailerIntoItsBayAndAWrongWayDriverDoesNot) {
  // the bay lies behind, 3 m to the side, between two standing boxes: the trailer's axles follow a path onto
  // its line; the tractor's steering holds the hitch angle that curves them so
  const Reversal good = reverse_into_bay({});
  ASSERT_EQ(good.metrics.moves_completed, 1);
  std::printf("reversed in %.1f s: %.3f m off, %.2f deg skew, hitch at most %.2f rad, score %.0f\n",
              good.metrics.time_s, good.metrics.placement_offset_m.at(0),
              good.metrics.placement_skew_deg.at(0), good.worst_hitch_rad, good.score);
  EXPECT_LT(good.metrics.placement_offset_m[0], 0.3);
  EXPECT_LT(good.metrics.placement_skew_deg.at(0), 2.0);
  EXPECT_EQ(good.metrics.collisions, 0);
  EXPECT_EQ(good.metrics.jackknifes, 0);
  EXPECT_GT(good.worst_hitch_rad, 0.05);  // it did turn the trailer
  EXPECT_GE(good.score, 70.0);

  // steering the way the trailer's rear is to go, the hitch angle runs away: a jack-knife or a box hit
  const Reversal bad = reverse_into_bay({.reverse_steering_wrong = true});
  std::printf("wrong way: hitch at most %.2f rad, %d jack-knives, %d collisions, %d moves, score %.0f\n",
              bad.worst_hitch_rad, bad.metrics.jackknifes, bad.metrics.collisions,
              bad.metrics.moves_completed, bad.score);
  EXPECT_EQ(bad.metrics.moves_completed, 0);
  EXPECT_GE(bad.metrics.jackknifes + bad.metrics.collisions, 1);
  EXPECT_LE(bad.score, good.score - 30.0 - 20.0);  // the exercise's 30 per jack-knife, 20 per move not made
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

// A trailer laden from the start shows its payload: an ISO box of its deck's length on the deck, painted
// with an ISO 6346 code, riding the trailer wherever it goes; an empty trailer shows none. The trailer's
// look is its kind's.
TEST(TractorTrailer, ALadenTrailerCarriesItsBoxOnTheDeckAndAnEmptyOneNone) {
  const ExerciseSettings laden = io::load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_semi_reverse.yaml");
  Simulation sim(laden.scenario);
  const scene::SceneDescription scene = sim.scene();
  const auto named = [&](const std::string& visual) {
    for (std::size_t n = 0; n < scene.entities.size(); ++n)
      if (scene.entities[n].visual == visual) return static_cast<int>(n);
    return -1;
  };
  const int trailer = named("trailer.semi"), box = named("container.40ft");
  ASSERT_GE(trailer, 0);
  ASSERT_GE(box, 0);
  const std::string& code = scene.entities[static_cast<std::size_t>(box)].name;
  ASSERT_EQ(code.size(), 11u);
  EXPECT_EQ(code, io::iso6346_code(code.substr(0, 4), std::stoi(code.substr(4, 6))));  // its check digit
  drive(sim, 20.0, 2.0, 0.4);                                                          // away on a curve
  const std::unique_ptr<scene::Snapshot> s = sim.snapshot();
  const core::Pose deck = s->entities[static_cast<std::size_t>(trailer)].pose;
  const core::Pose on = s->entities[static_cast<std::size_t>(box)].pose;
  const core::Vec3 local = deck.to_local(on.position);
  std::printf("the box on the deck: %.4f %.4f %.4f m in the trailer's frame\n", local.x, local.y, local.z);
  EXPECT_NEAR(local.x, 0.0, 1e-9);
  EXPECT_NEAR(local.y, 0.0, 1e-9);
  EXPECT_NEAR(local.z, 0.3 + 2.591 / 2.0, 1e-9);  // the deck's top plus the box's half height
  EXPECT_GT(core::length(deck.position - laden.scenario.machine.as<TractorSetup>().start.position_m), 10.0)
      << "it went somewhere";

  ExerciseSettings empty = laden;
  empty.scenario.machine.as<TractorSetup>().start.trailer->payload_half_extents_m.reset();
  const scene::SceneDescription bare = Simulation(empty.scenario).scene();
  EXPECT_TRUE(std::none_of(
      bare.entities.begin(), bare.entities.end(),
      [](const scene::SceneDescription::Entity& e) { return e.visual.starts_with("container"); }));
}

}  // namespace
}  // namespace harbour::sim
