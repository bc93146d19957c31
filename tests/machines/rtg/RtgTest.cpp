// The rubber-tyred gantry: its tyres, travel, steering and wheel turn, its spreader's pendulum, its block's
// 1-over-5 stacking, and the autopilot clearing its exercise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/machines/rtg/Files.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"
#include "harbour/sim/Weather.h"

namespace harbour::sim {
namespace {

constexpr double kG = 9.80665;

ExerciseSettings truck_to_block() {
  return io::load_exercise(HARBOUR_DATA_DIR "/exercises/rtg_truck_to_block.yaml");
}

RubberTyredGantry& rtg(Simulation& simulation) {
  return dynamic_cast<RubberTyredGantry&>(simulation.machine());
}

// Neutral controls with some set by label.
scene::Controls with(const Simulation& simulation,
                     std::initializer_list<std::pair<const char*, double>> values) {
  const scene::ControlTable& table = simulation.control_table();
  scene::Controls c = table.neutral();
  for (const auto& [label, value] : values) {
    const scene::ControlKind kind =
        std::string(label) == "wheel_turn" ? scene::ControlKind::kSwitch : scene::ControlKind::kAxis;
    c.value[static_cast<std::size_t>(table.slot(label, kind))] = value;
  }
  return c;
}

// Steps `seconds` with these controls.
void run(Simulation& simulation, const scene::Controls& controls, double seconds) {
  const auto steps = static_cast<int>(std::lround(seconds / Simulation::kStep_s));
  for (int k = 0; k < steps; ++k)
    simulation.step(controls);
}

// The exercise's scene without its boxes and truck (an empty yard).
ScenarioSettings empty_yard() {
  ScenarioSettings scenario = truck_to_block().scenario;
  scenario.containers.clear();
  scenario.trucks.trucks = 0;
  return scenario;
}

TEST(Rtg, ItsEightTyresCarryItsWeight) {
  // standing, the tyres' sag is the crane's weight over their stiffness: the frame's centre sits that much
  // under its unladen height
  Simulation simulation(truck_to_block().scenario);
  const RubberTyredGantry& c = rtg(simulation);
  for (int k = 0; k < 5000; ++k)
    simulation.step(simulation.control_table().neutral());
  const RtgSettings& s = c.settings();
  const double weight_n = (s.frame_mass_kg + s.trolley_mass_kg + s.rig.spreader.mass_kg) * kG;
  const double sag = weight_n / (8.0 * s.tyre.vertical_stiffness_n_per_m);
  const double z = simulation.world().pose(c.frame_body()).position.z;
  std::printf("frame centre %.4f m, statics %.4f m (sag %.1f mm)\n", z, s.frame_centre_height_m - sag,
              sag * 1e3);
  EXPECT_NEAR(z, s.frame_centre_height_m - sag, 0.1 * sag);
  EXPECT_LT(std::abs(c.yaw_rad()), 1e-4);
}
TEST(Rtg, TravelsAtItsPublishedSpeedAndStopsOnItsRamp) {
  Simulation simulation(empty_yard());
  const RubberTyredGantry& c = rtg(simulation);
  run(simulation, with(simulation, {{"gantry", 1.0}}), 20.0);
  const double speed = c.travel_speed_mps();
  std::printf("empty gantry speed %.3f m/s = %.1f m/min (published 130)\n", speed, speed * 60.0);
  EXPECT_NEAR(speed * 60.0, 130.0, 0.02 * 130.0);
  EXPECT_LT(std::abs(c.lane_offset_m()),
            0.05);  // the tyres roll along the frame's y: straight within tyre slip
  // lever released: the drive's deceleration ramp, then the holding brakes
  const double y0 = c.gantry_y_m();
  run(simulation, simulation.control_table().neutral(), 15.0);
  const double stop = c.gantry_y_m() - y0;
  const double ramp = speed * speed / (2.0 * c.settings().gantry_drive.deceleration_mps2);
  std::printf("stopping distance %.2f m, v^2/2a %.2f m\n", stop, ramp);
  EXPECT_NEAR(stop, ramp, 0.05 * ramp);
  // and the brakes hold it there: the frame only rocks on its tyres with the spreader's swing (±5 mm)
  const double stopped_at = c.gantry_y_m();
  run(simulation, simulation.control_table().neutral(), 10.0);
  EXPECT_LT(std::abs(c.gantry_y_m() - stopped_at), 0.01);
}

// Its gantry's wheel motors are measured as the tractor's drive: cruising along the block at full speed in
// still air, they deliver what rolling resistance takes, Crr W over the distance (W the crane's weight on its
// tyres), and the air's drag on its wind areas.
TEST(Rtg, ItsGantryDriveDeliversWhatRollingResistanceAndDragTake) {
  ScenarioSettings scenario = empty_yard();
  Simulation simulation(scenario);
  const RubberTyredGantry& c = rtg(simulation);
  const scene::Controls travel = with(simulation, {{"gantry", 1.0}});
  run(simulation, travel, 20.0);  // up to speed
  const RtgSettings& s = c.settings();
  const double weight_n = (s.frame_mass_kg + s.trolley_mass_kg + s.rig.spreader.mass_kg) * kG;
  double delivered_j = 0.0, drag_j = 0.0;
  const double y0 = c.gantry_y_m();
  for (int k = 0; k < 10000; ++k) {
    for (const WindArea& area : c.wind_areas()) {
      if (area.body == physics::kWorld) continue;
      const core::Vec3 v = simulation.world().linear_velocity(area.body);
      drag_j -= dot(box_drag({}, v, simulation.world().pose(area.body), area.half_extents_m,
                             scenario.drag_coefficient, scenario.weather.air_density_kg_m3),
                    v) *
                Simulation::kStep_s;
    }
    simulation.step(travel);
    delivered_j += c.tally().travel_power_w * Simulation::kStep_s;
  }
  const double rolling_j = s.tyre.rolling_resistance * weight_n * std::abs(c.gantry_y_m() - y0);
  std::printf("gantry cruising 10 s: drive %.0f J against rolling %.0f J + drag %.0f J = %.0f J\n",
              delivered_j, rolling_j, drag_j, rolling_j + drag_j);
  EXPECT_NEAR(delivered_j, rolling_j + drag_j, 0.01 * (rolling_j + drag_j));
}

RtgSettings rtg_settings() {
  return empty_yard().machine.as<RtgSetup>().crane;
}

// The empty yard in a steady wind blowing along the block (from the north: towards -y), with the gantry's
// holding brakes at `brake_force_n`: how far the frame moves at the ground (between its wheels: the frame
// itself leans a few cm on its tyres' springs) in `seconds` after a second's settling, and the wind's force
// on the crane along the block then [N].
struct WindHold {
  double moved_m = 0.0, wind_force_n = 0.0, mass_kg = 0.0, weight_n = 0.0;
};
WindHold braked_in_wind(double wind_mps, double brake_force_n, double seconds,
                        bool across_the_block = false) {
  ScenarioSettings scenario = empty_yard();
  scenario.weather.wind_mean_mps = wind_mps;
  scenario.weather.wind_from_rad = across_the_block ? std::numbers::pi / 2.0 : 0.0;  // from the east: to -x
  scenario.weather.turbulence_intensity = 0.0;
  scenario.machine.as<RtgSetup>().crane.gantry_drive.brake_force_n = brake_force_n;
  Simulation simulation(scenario);
  const RubberTyredGantry& c = rtg(simulation);
  const auto at_ground_y = [&] {
    const core::Vec3 p =
        simulation.world().point_position(c.frame_body(), {0.0, 0.0, -c.settings().frame_centre_height_m});
    return across_the_block ? p.x : p.y;
  };
  run(simulation, simulation.control_table().neutral(), 1.0);
  const double from = at_ground_y();
  run(simulation, simulation.control_table().neutral(), seconds);
  EXPECT_FALSE(simulation.diverged()) << simulation.divergence();
  WindHold out;
  out.moved_m = at_ground_y() - from;
  for (const WindArea& area : c.wind_areas()) {
    const core::Vec3 drag =
        box_drag(simulation.weather().wind(), {}, simulation.world().pose(area.body), area.half_extents_m,
                 scenario.drag_coefficient, scenario.weather.air_density_kg_m3);
    out.wind_force_n += across_the_block ? drag.x : drag.y;
  }
  const RtgSettings& s = c.settings();
  out.mass_kg = s.frame_mass_kg + s.trolley_mass_kg + s.rig.spreader.mass_kg;
  out.weight_n = out.mass_kg * kG;
  return out;
}

TEST(Rtg, ItsBrakesHoldItInA25MpsWindAlongTheBlockAndItRollsAwayWhenTheWindExceedsThem) {
  const double brakes_n = rtg_settings().gantry_drive.brake_force_n;
  const WindHold held = braked_in_wind(25.0, brakes_n, 60.0);
  std::printf("25 m/s along the block (%.0f kN on the crane), brakes %.0f kN: moved %.5f m in 60 s\n",
              -held.wind_force_n / 1000.0, brakes_n / 1000.0, held.moved_m);
  EXPECT_LT(held.wind_force_n, -20000.0);  // the wind pushes it hard towards -y
  EXPECT_LT(std::abs(held.moved_m), 0.01);
  // brakes worn to half what the wind and the rolling resistance take: it rolls away at
  // a = (F - B - crr W) / M
  const double crr = rtg_settings().tyre.rolling_resistance;
  const double worn_n = 0.5 * (-held.wind_force_n - crr * held.weight_n);
  ASSERT_GT(worn_n, 0.0);
  const double seconds = 10.0;
  const WindHold slid = braked_in_wind(25.0, worn_n, seconds);
  const double expected_mps2 = (-slid.wind_force_n - worn_n - crr * slid.weight_n) / slid.mass_kg;
  const double measured_mps2 = -2.0 * slid.moved_m / (seconds * seconds);
  std::printf("brakes %.1f kN: rolled %.2f m in %.0f s, %.4f m/s^2 against %.4f\n", worn_n / 1000.0,
              slid.moved_m, seconds, measured_mps2, expected_mps2);
  EXPECT_NEAR(measured_mps2, expected_mps2, 0.15 * expected_mps2);
}

TEST(Rtg, BrakedItStandsInA25MpsWindAcrossTheBlockOnItsTyresGrip) {
  // across its wheels nothing rolls: the tyres' grip holds it (static friction up to µ F_z each)
  const WindHold held = braked_in_wind(25.0, rtg_settings().gantry_drive.brake_force_n, 60.0, true);
  std::printf("25 m/s across the block (%.0f kN on the crane): moved %.5f m in 60 s\n",
              -held.wind_force_n / 1000.0, held.moved_m);
  EXPECT_LT(held.wind_force_n, -20000.0);  // towards -x
  EXPECT_LT(std::abs(held.moved_m), 0.01);
}

TEST(Rtg, ASteeringBiasCurvesItsPathAsTheSteeringGeometrySaysAndTheOperatorCorrectsIt) {
  // front and rear bogies steered ±δ turn the frame about its middle on a radius R = b / (2 tan δ): after a
  // distance s along the block it is s² / 2R off its line
  ScenarioSettings scenario = empty_yard();
  const double bias = 0.5 * std::numbers::pi / 180.0;
  scenario.machine.as<RtgSetup>().start.steer_bias_rad = bias;
  Simulation drifting(scenario);
  run(drifting, with(drifting, {{"gantry", 1.0}}), 22.0);
  const RubberTyredGantry& c = rtg(drifting);
  const double s = c.gantry_y_m();
  const double radius = c.settings().wheelbase_m / (2.0 * std::tan(bias));
  const double expected = -s * s / (2.0 * radius);  // + steering turns left: towards -x going +y
  std::printf("after %.1f m: %.3f m off the line, kinematics %.3f m (R %.0f m)\n", s, c.lane_offset_m(),
              expected, radius);
  EXPECT_NEAR(c.lane_offset_m(), expected, 0.15 * std::abs(expected));
  // the operator holds the line by steering against the bias
  Simulation held(scenario);
  run(held, with(held, {{"gantry", 1.0}, {"steer", -bias / rtg(held).settings().max_steer_rad}}), 22.0);
  std::printf("steered against it: %.3f m off\n", rtg(held).lane_offset_m());
  EXPECT_LT(std::abs(rtg(held).lane_offset_m()), 0.05);
}

TEST(Rtg, ItsWheelsTurnForABlockChangeOnlyAtAStandstill) {
  Simulation simulation(empty_yard());
  const RubberTyredGantry& c = rtg(simulation);
  run(simulation, with(simulation, {{"gantry", 1.0}}), 5.0);
  run(simulation, with(simulation, {{"gantry", 1.0}, {"wheel_turn", 1.0}}), 2.0);
  EXPECT_EQ(c.wheel_turn_refusals(), 1u);  // asked once while travelling: refused, counted once
  EXPECT_EQ(c.wheel_turn(), 0.0);
  run(simulation, with(simulation, {{"wheel_turn", 1.0}}), 15.0);  // stopped, the switch still asking
  EXPECT_EQ(c.wheel_turn(), 0.0) << "a refused turn waits for the switch to go back";
  run(simulation, simulation.control_table().neutral(), 1.0);
  run(simulation, with(simulation, {{"wheel_turn", 1.0}}), 30.0);
  EXPECT_NEAR(c.wheel_turn(), 30.0 / c.settings().wheel_turn_time_s, 1e-3);
  // the gantry lever does nothing while the wheels turn
  run(simulation, with(simulation, {{"wheel_turn", 1.0}, {"gantry", 1.0}}), 5.0);
  EXPECT_LT(std::abs(c.travel_speed_mps()), 0.01);
  run(simulation, with(simulation, {{"wheel_turn", 1.0}}), 30.0);
  EXPECT_EQ(c.wheel_turn(), 1.0);
  // turned: it travels across the block
  const core::Vec3 start = simulation.world().pose(c.frame_body()).position;
  run(simulation, with(simulation, {{"wheel_turn", 1.0}, {"gantry", 0.3}}), 10.0);
  const core::Vec3 at = simulation.world().pose(c.frame_body()).position;
  std::printf("turned: %.2f m across, %.3f m along\n", at.x - start.x, at.y - start.y);
  EXPECT_GT(at.x - start.x, 3.0);
  EXPECT_LT(std::abs(at.y - start.y), 0.05);
  EXPECT_EQ(c.wheel_turn_refusals(), 1u);
}

TEST(Rtg, TheSpreaderSwingsWithThePeriodOfItsPendulum) {
  Simulation simulation(empty_yard());
  const RubberTyredGantry& c = rtg(simulation);
  run(simulation, with(simulation, {{"trolley", -1.0}}), 3.0);  // a trolley start sets it swinging
  run(simulation, simulation.control_table().neutral(), 5.0);
  // upward zero crossings of the spreader's offset from under the trolley
  std::vector<double> crossings;
  double last = 0.0;
  const double length = c.pendulum_length_m();
  while (crossings.size() < 6) {
    simulation.step(simulation.control_table().neutral());
    const double offset = c.spreader_pose().position.x - c.trolley_x_m();
    if (last < 0.0 && offset >= 0.0) crossings.push_back(simulation.time_s());
    last = offset;
  }
  const double period = (crossings.back() - crossings.front()) / 5.0;
  const double expected = 2.0 * std::numbers::pi * std::sqrt(length / kG);
  std::printf("swing period %.3f s, 2 pi sqrt(L/g) %.3f s (L %.2f m)\n", period, expected, length);
  EXPECT_NEAR(period, expected, 0.03 * expected);
}

// The trolley's drive is the RTG's measured travel work: brought up to speed from rest, what it delivered is
// the kinetic energy of the trolley and of the spreader swinging under it, and the spreader's rise.
TEST(Rtg, ItsTrolleyDriveDeliversTheWorkThatMovesTheTrolleyAndTheSpreader) {
  Simulation simulation(empty_yard());
  const RubberTyredGantry& c = rtg(simulation);
  const physics::PhysicsWorld& world = simulation.world();
  const physics::BodyId spreader = *c.gripper_body();
  const double start_z = world.pose(spreader).position.z;
  double work = 0.0;
  const scene::Controls out = with(simulation, {{"trolley", -1.0}});
  for (int k = 0; k < 3500; ++k) {  // 0.4 m/s^2 to its 1.17 m/s in 2.9 s
    simulation.step(out);
    work += c.tally().travel_power_w * Simulation::kStep_s;
  }
  const auto kinetic = [&](physics::BodyId body) {
    const core::Vec3 v = world.linear_velocity(body);
    return 0.5 * world.mass_kg(body) * core::dot(v, v);
  };
  const double energy = kinetic(c.trolley_body()) + kinetic(spreader) +
                        world.mass_kg(spreader) * kG * (world.pose(spreader).position.z - start_z);
  std::printf("trolley drive: %.0f J delivered; trolley and spreader %.0f J (trolley at %.3f m/s)\n", work,
              energy, core::length(world.linear_velocity(c.trolley_body())));
  EXPECT_GT(energy, 15000.0);  // a real run: 30 t at about 1.2 m/s
  // within 1 %: the ropes' own motion and the frame's sway on its tyres are left out
  EXPECT_NEAR(work, energy, 0.01 * energy);
}

TEST(Rtg, ItCarriesAHighCubeOneOverFiveAndTheBlockStacksFiveHigh) {
  // at the upper limit a carried high cube's underside clears a five-high stack (1-over-5)
  const RtgSettings s = io::load_rtg(HARBOUR_DATA_DIR "/machines/rtg.yaml");
  const double high_cube = 2.896;
  const double lift = s.rig.upper_limit_m - 0.5 * s.rig.spreader.height_m;
  const double clearance = lift - high_cube - 5 * high_cube;
  std::printf("lift %.2f m under the spreader: a carried high cube clears five high by %.2f m\n", lift,
              clearance);
  EXPECT_NEAR(lift, 18.0, 1e-9);  // published
  EXPECT_GT(clearance, 0.3);
  EXPECT_LT(clearance, high_cube);  // not six high
  // a sixth tier is no slot of the block
  YardBlock block;
  block.bays = 5;
  std::string why;
  EXPECT_TRUE(block.slot_centre(2, 1, 5, why).has_value());
  EXPECT_FALSE(block.slot_centre(2, 1, 6, why).has_value());
  EXPECT_NE(why.find("stacks 5 high"), std::string::npos) << why;
}

TEST(Rtg, TheAutopilotStacksTheTrucksBoxAndAKeyframeContinuesBitForBit) {
  const ExerciseSettings exercise = truck_to_block();
  Simulation simulation(exercise.scenario);
  std::unique_ptr<Pilot> pilot = make_pilot(exercise);
  Evaluator evaluator(exercise);
  std::vector<std::uint8_t> keyframe;
  std::vector<scene::Controls> after_keyframe;
  std::uint64_t hash = 0;
  constexpr std::int64_t kKeyframeStep = 60000, kCompareStep = 63000;
  while (!evaluator.finished() && simulation.time_s() < exercise.rules.time_limit_s &&
         !simulation.diverged()) {
    if (simulation.steps() == kKeyframeStep) keyframe = simulation.save_state();
    const scene::Controls c = pilot->next(simulation);
    if (simulation.steps() >= kKeyframeStep && simulation.steps() < kCompareStep) after_keyframe.push_back(c);
    simulation.step(c);
    evaluator.observe(simulation, c);
    if (simulation.steps() == kCompareStep) hash = simulation.state_hash();
  }
  ASSERT_FALSE(simulation.diverged()) << simulation.divergence();
  const Metrics& m = evaluator.metrics();
  ASSERT_EQ(m.moves_completed, 1);
  std::printf("autopilot: %.1f s, placed %.3f m off, %.2f deg skew, score %.0f\n", simulation.time_s(),
              m.placement_offset_m[0], m.placement_skew_deg[0], evaluator.score().total);
  EXPECT_LT(m.placement_offset_m[0], exercise.moves[0].tolerance_m);
  EXPECT_EQ(m.collisions, 0);
  EXPECT_GE(evaluator.score().total, exercise.rules.pass_score);
  EXPECT_EQ(simulation.trucks()->departed(),
            1);  // the truck left once its box was off and the spreader clear

  // a keyframe taken a minute in continues to the same state on the same controls
  Simulation resumed(exercise.scenario);
  resumed.restore_state(keyframe);
  for (const scene::Controls& c : after_keyframe)
    resumed.step(c);
  EXPECT_EQ(resumed.state_hash(), hash);
}

// An exercise driven to its end by the autopilot with these defects, and how far the crane strayed off its
// line on the way.
struct Drive {
  Metrics metrics;
  double score = 0.0;
  double time_s = 0.0;
  double worst_lane_offset_m = 0.0;
};
Drive drive_exercise(const char* name, OperatorDefects defects = {}) {
  const ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR "/exercises/") + name + ".yaml");
  Simulation simulation(exercise.scenario);
  GantryAutopilot pilot(exercise, defects);
  Evaluator evaluator(exercise);
  Drive d;
  while (!evaluator.finished() && simulation.time_s() < exercise.rules.time_limit_s &&
         !simulation.diverged()) {
    const scene::Controls c = pilot.next(simulation);
    simulation.step(c);
    evaluator.observe(simulation, c);
    d.worst_lane_offset_m = std::max(d.worst_lane_offset_m, std::abs(rtg(simulation).lane_offset_m()));
  }
  EXPECT_FALSE(simulation.diverged()) << simulation.divergence();
  d.metrics = evaluator.metrics();
  d.score = evaluator.score().total;
  d.time_s = simulation.time_s();
  return d;
}

TEST(Rtg, TheAutopilotDigsTheWantedBoxOutFromUnderTwoOthersAndSetsItOnTheTruck) {
  const Drive d = drive_exercise("rtg_rehandle");
  std::printf("re-handle: %.1f s, 3 moves placed %.3f, %.3f, %.3f m off, score %.0f\n", d.time_s,
              d.metrics.placement_offset_m.at(0), d.metrics.placement_offset_m.at(1),
              d.metrics.placement_offset_m.at(2), d.score);
  ASSERT_EQ(d.metrics.moves_completed, 3);
  EXPECT_EQ(d.metrics.collisions, 0);  // setting the spreader down on a box to lift is a landing
  EXPECT_EQ(d.metrics.hard_landings, 0);
  EXPECT_GE(d.score, 70.0);
}

TEST(Rtg, OnAGantryMoveTheOperatorSteersAgainstTheBiasAndABadOneHitsTheNextBlock) {
  // a 0.5 deg bias curves the crane 2.0 m off its line over the 38.4 m to bay 14 (s^2 / 2R), where the next
  // block's boxes stand with their faces 1.55 m outside the line of its -x tyres (the bogies' outer parts
  // meet them some 0.7 m off the line)
  const Drive good = drive_exercise("rtg_gantry_move");
  std::printf(
      "gantry move: %.1f s, placed %.3f m off, %.2f deg skew, %.3f m off its line at worst, score %.0f\n",
      good.time_s, good.metrics.placement_offset_m.at(0), good.metrics.placement_skew_deg.at(0),
      good.worst_lane_offset_m, good.score);
  ASSERT_EQ(good.metrics.moves_completed, 1);
  EXPECT_EQ(good.metrics.collisions, 0);
  EXPECT_EQ(good.metrics.unwarned_gantry_travel, 0);
  EXPECT_LT(good.worst_lane_offset_m, 0.3);
  EXPECT_GE(good.score, 70.0);

  // never steering, no horn: the legs run into the next block's stacks, and the travel went unwarned
  const Drive bad = drive_exercise("rtg_gantry_move", {.never_steer = true, .skip_horn = true});
  std::printf("bad operator: %.3f m off its line, %d collisions (%d with stacks), %d unwarned, score %.0f\n",
              bad.worst_lane_offset_m, bad.metrics.collisions, bad.metrics.container_collisions,
              bad.metrics.unwarned_gantry_travel, bad.score);
  EXPECT_GT(bad.worst_lane_offset_m, 0.5);
  EXPECT_GE(bad.metrics.container_collisions, 1);
  EXPECT_EQ(bad.metrics.unwarned_gantry_travel, 1);
  EXPECT_LE(bad.score, good.score - 10.0 - 2.0);  // the documented 10 per collision, 2 per unwarned travel
}

}  // namespace
}  // namespace harbour::sim
