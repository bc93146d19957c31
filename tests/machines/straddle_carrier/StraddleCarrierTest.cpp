// The straddle carrier: its drive and steering against the drivetrain's limit and Ackermann's circle, its
// hoist against the statics of its falls, and its scripted driver stacking a box 1-over-3.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/parts/PurePursuit.h"
#include "harbour/machines/straddle_carrier/Files.h"
#include "harbour/machines/straddle_carrier/StraddleCarrier.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"

namespace harbour::sim {
namespace {

constexpr double kG = 9.80665;
const char* const kStack = HARBOUR_DATA_DIR "/exercises/straddle_carrier_stack.yaml";

double& control(scene::Controls& c, const scene::ControlTable& table, const char* label) {
  return c.value[static_cast<std::size_t>(table.find(label))];
}

// The selector in forward, the accelerator floored, everything else at rest.
scene::Controls full_throttle_forward(const scene::ControlTable& table) {
  scene::Controls c = table.neutral();
  control(c, table, "direction") = 2.0;
  control(c, table, "throttle") = 1.0;
  return c;
}

TEST(StraddleCarrier, AtRestEachOfItsEightFallsCarriesAnEighthOfTheSpreader) {
  Simulation sim(io::load_exercise(kStack).scenario);
  const auto& m = dynamic_cast<const StraddleCarrier&>(sim.machine());
  const scene::Controls neutral = sim.control_table().neutral();
  for (int k = 0; k < 2000; ++k)
    sim.step(neutral);
  // the falls carry the spreader's weight and half their own: the load display (tared, in steps of 0.1 t)
  // reads nothing
  EXPECT_LT(std::abs(m.spreader_hoist().net_load_t()), 0.1);
  // the most loaded fall: an eighth of the spreader and its own weight (the rope's, 1.5-11 m of it)
  const double spreader_n = m.settings().rig.spreader.mass_kg * kG;
  const double tension = m.spreader_hoist().hoist().highest_tension_n();
  EXPECT_GT(tension, spreader_n / 8.0);
  EXPECT_LT(tension, spreader_n / 8.0 + 11.0 * 2.0 * kG * 1.5);
  // and it stands still on its brakes-off tyres, level
  EXPECT_LT(std::abs(m.forward_mps()), 1e-3);
  std::printf("straddle carrier at rest: %.0f N in the most loaded fall against %.0f N (an eighth)\n",
              tension, spreader_n / 8.0);
}

TEST(StraddleCarrier, FullThrottleOnTheFlatReachesItsTopGearsEngineLimit) {
  // the drivetrain's top speed: the curve's last engine speed in top gear, v = omega r / (ratio final)
  Simulation sim(io::load_exercise(kStack).scenario);
  const auto& m = dynamic_cast<const StraddleCarrier&>(sim.machine());
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = full_throttle_forward(table);
  double top = 0.0;
  for (int k = 0; k < static_cast<int>(25.0 / Simulation::kStep_s); ++k) {
    sim.step(c);
    top = std::max(top, m.forward_mps());
  }
  const DrivetrainSettings& d = m.settings().chassis.drivetrain;
  const double limit_mps = d.torque_curve.back().first * 2.0 * std::numbers::pi / 60.0 /
                           (d.gear_ratios.back() * d.final_drive) * m.settings().chassis.tyre.radius_m;
  EXPECT_NEAR(top, limit_mps, 0.03 * limit_mps);
  EXPECT_NEAR(limit_mps * 3.6, 30.0, 1.0);  // the class's published top speed
  std::printf("straddle carrier top speed %.2f m/s (%.1f km/h) against %.2f m/s\n", top, top * 3.6,
              limit_mps);
}

TEST(StraddleCarrier, AtFullLockEveryWheelSteeredItTurnsOnTheAckermannCircleAboutItsMiddle) {
  // all-wheel steering: the turn's centre across from the portal's middle, L / tan(delta) from it
  Simulation sim(io::load_exercise(kStack).scenario);
  const auto& m = dynamic_cast<const StraddleCarrier&>(sim.machine());
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = table.neutral();
  control(c, table, "direction") = 2.0;
  control(c, table, "steer") = 1.0;
  for (int k = 0; k < static_cast<int>(20.0 / Simulation::kStep_s); ++k) {
    control(c, table, "throttle") = std::clamp(0.3 * (1.0 - m.forward_mps()), 0.0, 1.0);
    sim.step(c);
  }
  EXPECT_NEAR(m.chassis().reference_x_m(), 0.0, 1e-12);
  const double expected = m.chassis().steer_base_m() / std::tan(m.settings().chassis.max_steer_rad);
  const core::Vec3 v = sim.world().point_velocity(m.body(), {0, 0, 0});
  const double radius = std::hypot(v.x, v.y) / std::abs(sim.world().angular_velocity(m.body()).z);
  EXPECT_NEAR(radius, expected, 0.05 * expected);
  std::printf("straddle carrier at full lock: %.3f m against L / tan(delta) = %.3f m\n", radius, expected);
}

// Driven along the row at full throttle for 5 s, stopped hard on its brakes (the spreader swinging under the
// portal), then the pedal released in neutral for 20 s with the parking brake set or not: how far its
// footprint (the ground under its middle) goes then, its fastest speed over the ground, how far the spreader
// swings from under the portal's centre of mass and how far that rocks on the tyres.
struct AfterAStop {
  double travelled_m = 0.0, fastest_mps = 0.0, swing_m = 0.0, rocking_m = 0.0;
};
AfterAStop after_a_hard_stop(bool parking_brake) {
  Simulation sim(io::load_exercise(kStack).scenario);
  const auto& m = dynamic_cast<const StraddleCarrier&>(sim.machine());
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = full_throttle_forward(table);
  for (int k = 0; k < 5000; ++k)
    sim.step(c);
  control(c, table, "throttle") = 0.0;
  control(c, table, "brake") = 1.0;
  for (int k = 0; k < 4000; ++k)
    sim.step(c);
  control(c, table, "brake") = 0.0;
  control(c, table, "direction") = 1.0;
  control(c, table, "parking_brake") = parking_brake ? 1.0 : 0.0;
  AfterAStop out;
  const double ground_z = m.settings().chassis.axles.front().hub_z_m - m.settings().chassis.tyre.radius_m;
  const auto footprint = [&] { return sim.world().pose(m.body()).to_parent({0.0, 0.0, ground_z}); };
  const core::Vec3 from = footprint(), top_from = sim.world().pose(m.body()).position;
  for (int k = 0; k < 20000; ++k) {
    sim.step(c);
    out.fastest_mps = std::max(out.fastest_mps, std::abs(m.forward_mps()));
    const core::Vec3 portal = sim.world().pose(m.body()).position, spreader = m.spreader_pose().position;
    out.swing_m = std::max(out.swing_m, std::hypot(spreader.x - portal.x, spreader.y - portal.y));
    out.rocking_m = std::max(out.rocking_m, std::hypot(portal.x - top_from.x, portal.y - top_from.y));
  }
  const core::Vec3 to = footprint();
  out.travelled_m = std::hypot(to.x - from.x, to.y - from.y);
  const std::vector<std::string> names = sim.scene().indicators;
  const auto lamp = std::find(names.begin(), names.end(), "lamp_parking_brake");
  EXPECT_NE(lamp, names.end());
  if (lamp != names.end()) {
    EXPECT_EQ(sim.snapshot()->indicators[static_cast<std::size_t>(lamp - names.begin())],
              parking_brake ? 1.0 : 0.0);
  }
  return out;
}

TEST(StraddleCarrier, TheParkingBrakeHoldsItStillWhileTheSpreaderSwingsUnderIt) {
  // released, the portal rolls to and fro against its swinging spreader (only rolling resistance between its
  // wheels and the ground); on its spring brakes its wheels stand while the tall portal still rocks on its
  // tyres, and its speedometer (the wheels' speed) reads nothing
  const AfterAStop parked = after_a_hard_stop(true), free = after_a_hard_stop(false);
  std::printf(
      "after a hard stop, spreader swinging %.2f m: parked: wheels moved %.4f m, fastest %.4f m/s, the "
      "portal's top rocking %.3f m; released: wheels moved %.3f m, fastest %.3f m/s\n",
      parked.swing_m, parked.travelled_m, parked.fastest_mps, parked.rocking_m, free.travelled_m,
      free.fastest_mps);
  EXPECT_GT(parked.swing_m, 0.3);
  EXPECT_LT(parked.travelled_m, 0.005);
  EXPECT_LT(parked.fastest_mps, 0.005);
  EXPECT_GT(free.fastest_mps, 0.05);
}

TEST(StraddleCarrier, AHardStopThatSwingsTheEmptySpreaderHighIsNoLoadDrop) {
  // from 5 m/s to a stop on full brake: the spreader swings up and sinks back along its arc faster than a
  // fall's speed (1.0 m/s here), but its drum stands, and a fall is the drum running free
  const ExerciseSettings e = io::load_exercise(kStack);
  Simulation sim(e.scenario);
  Evaluator evaluator(e);
  const auto& m = dynamic_cast<const StraddleCarrier&>(sim.machine());
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = full_throttle_forward(table);
  double sampled_z_m = m.attachment_bottom_z_m(), fastest_sinking_mps = 0.0, fastest_lowering_mps = 0.0;
  for (int k = 0; k < 15000; ++k) {
    if (k == 5000) {
      control(c, table, "throttle") = 0.0;
      control(c, table, "brake") = 1.0;
    }
    sim.step(c);
    evaluator.observe(sim, c);
    fastest_lowering_mps = std::max(fastest_lowering_mps, m.lowering_speed_mps());
    if (k % 100 == 99) {  // over 0.1 s
      const double z = m.attachment_bottom_z_m();
      fastest_sinking_mps = std::max(fastest_sinking_mps, (sampled_z_m - z) / 0.1);
      sampled_z_m = z;
    }
  }
  std::printf(
      "a hard stop: the spreader sank at up to %.2f m/s along its swing, its drum lowered at %.4f m/s; "
      "%d loads dropped\n",
      fastest_sinking_mps, fastest_lowering_mps, evaluator.metrics().load_drops);
  EXPECT_GT(fastest_sinking_mps, e.rules.load_drop_mps);
  EXPECT_LT(fastest_lowering_mps, 0.01);
  EXPECT_EQ(evaluator.metrics().load_drops, 0);
}

TEST(StraddleCarrier, TheAutopilotStacksTheBoxOverThreeHighAndAKeyframeContinuesExactly) {
  const ExerciseSettings e = io::load_exercise(kStack);
  Simulation sim(e.scenario);
  const std::unique_ptr<Pilot> pilot = make_pilot(e);
  Evaluator evaluator(e);
  std::vector<std::uint8_t> keyframe;  // taken as it carries the box over the stacks
  std::vector<scene::Controls> after;
  std::uint64_t hash_after = 0;
  double lowest_box_over_stack_m = 1e9;
  const auto& machine = dynamic_cast<const StraddleCarrier&>(sim.machine());
  while (!evaluator.finished() && sim.time_s() < e.rules.time_limit_s) {
    const scene::Controls c = pilot->next(sim);
    if (std::string(pilot->activity()) == "carry" && keyframe.empty()) keyframe = sim.save_state();
    if (!keyframe.empty() && after.size() < 2000) after.push_back(c);
    sim.step(c);
    if (after.size() == 2000 && hash_after == 0) hash_after = sim.state_hash();
    evaluator.observe(sim, c);
    // over the three-high stack (bay 06, y = 36 +- 6.1 m): the box's underside above its top
    if (const auto held = machine.held_item()) {
      const core::Pose box = sim.world().pose(*held);
      if (std::abs(box.position.y - 36.0) < 6.1 + 6.1)
        lowest_box_over_stack_m = std::min(lowest_box_over_stack_m, box.position.z - 1.448 - 3 * 2.896);
    }
  }
  const Metrics& m = evaluator.metrics();
  EXPECT_EQ(m.moves_completed, 1);
  ASSERT_EQ(m.placement_offset_m.size(), 1u);
  EXPECT_LT(m.placement_offset_m[0], 0.05);  // square on the stack below
  EXPECT_EQ(m.collisions, 0);
  EXPECT_GT(lowest_box_over_stack_m, 0.3);  // 1-over-3
  EXPECT_GE(evaluator.score().total, 90.0);
  std::printf("stacked 1-over-3 in %.1f s, %.3f m off, %.2f m over the three-high stack, score %.0f\n",
              m.time_s, m.placement_offset_m[0], lowest_box_over_stack_m, evaluator.score().total);
  ASSERT_EQ(after.size(), 2000u);
  Simulation again(e.scenario);
  again.restore_state(keyframe);
  for (const scene::Controls& c : after)
    again.step(c);
  EXPECT_EQ(again.state_hash(), hash_after);
}

TEST(StraddleCarrier, TheAutopilotCarriesTheBoxOutOfTheRowAlongTheRouteToTheQuayCranesTransferPoint) {
  const ExerciseSettings e = io::load_exercise(HARBOUR_DATA_DIR "/exercises/straddle_carrier_transfer.yaml");
  Simulation sim(e.scenario);
  const std::unique_ptr<Pilot> pilot = make_pilot(e);
  Evaluator evaluator(e);
  const auto& machine = dynamic_cast<const StraddleCarrier&>(sim.machine());
  double farthest_off_route_m = 0.0, fastest_kmh = 0.0;
  while (!evaluator.finished() && sim.time_s() < e.rules.time_limit_s) {
    const scene::Controls c = pilot->next(sim);
    sim.step(c);
    evaluator.observe(sim, c);
    fastest_kmh = std::max(fastest_kmh, std::abs(machine.forward_mps()) * 3.6);
    if (machine.held_item()) {  // laden: on its way from the row's line through the route to the target
      core::Vec3 p = sim.world().pose(machine.body()).position;
      p.z = 0.0;
      std::vector<core::Vec3> way = {{-40.0, 20.0, 0.0}};
      way.insert(way.end(), e.route_m.begin(), e.route_m.end());
      way.push_back({e.moves[0].target_m.x, e.moves[0].target_m.y, 0.0});
      farthest_off_route_m = std::max(farthest_off_route_m, core::length(p - point_ahead(way, p, 0.0)));
    }
  }
  const Metrics& m = evaluator.metrics();
  EXPECT_EQ(m.moves_completed, 1);
  ASSERT_EQ(m.placement_offset_m.size(), 1u);
  EXPECT_LT(m.placement_offset_m[0], 0.1);
  EXPECT_EQ(m.collisions, 0);
  EXPECT_EQ(m.overspeeds, 0);
  EXPECT_LT(fastest_kmh, 20.0);          // the yard's limit
  EXPECT_LT(farthest_off_route_m, 1.5);  // the corners cut by pure pursuit's lookahead, no more
  EXPECT_GE(evaluator.score().total, 90.0);
  std::printf(
      "carried to the transfer point in %.1f s, %.3f m off, %.2f m off the route at most, %.1f km/h at "
      "most, score %.0f\n",
      m.time_s, m.placement_offset_m[0], farthest_off_route_m, fastest_kmh, evaluator.score().total);
}

TEST(StraddleCarrier, BadFilesNameTheField) {
  const auto fails_with = [](const std::string& from, const std::string& to, const std::string& expected) {
    std::string text;
    {
      std::ifstream in(HARBOUR_DATA_DIR "/machines/straddle_carrier.yaml");
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    try {
      io::load_straddle_carrier(io::YamlFile::parse(text, "sc.yaml"), HARBOUR_DATA_DIR "/machines");
      ADD_FAILURE() << "accepted " << to;
    } catch (const io::DataError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  fails_with("{x_m: 3.3, half_track_m: 2.05, hub_z_m: -6.5, steered: true",
             "{x_m: 3.3, half_track_m: 2.05, hub_z_m: -6.5, steered: false", "machine.axles");
  fails_with("leg_y_m: 2.05", "leg_y_m: 1.3", "machine.portal.leg_y_m");
  fails_with("upper_limit_m: 12.8", "upper_limit_m: 13.5", "machine.hoist.upper_limit_m");
  fails_with("{label: hoist, kind: axis", "{label: hoist2, kind: axis", "machine.controls");
}

}  // namespace
}  // namespace harbour::sim
