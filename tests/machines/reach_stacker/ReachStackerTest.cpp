// The reach stacker's stability: its load chart from the statics of its support, and that statics against the
// multibody model tipping it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/reach_stacker/Files.h"
#include "harbour/machines/reach_stacker/ReachStackerAutopilot.h"
#include "harbour/machines/reach_stacker/ReachStackerStability.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"

namespace harbour::sim {
namespace {

constexpr double kG = 9.80665, kDt = 0.001;

ReachStackerSettings shipped() {
  return io::load_reach_stacker(HARBOUR_DATA_DIR "/machines/reach_stacker.yaml");
}

TEST(ReachStacker, ItsLoadChartGivesThePublishedRowRatings) {
  // published for the class: 45 t in the 1st row, 29 t in the 2nd, 15 t in the 3rd
  const ReachStackerSettings s = shipped();
  ASSERT_EQ(s.row_reach_m.size(), 3u);
  const double published_t[] = {45.0, 29.0, 15.0};
  for (std::size_t row = 0; row < 3; ++row) {
    const double rated_t = rated_load_kg(s, s.row_reach_m[row]) / 1000.0;
    EXPECT_NEAR(rated_t, published_t[row], 0.03 * published_t[row]) << "row " << row + 1;
    std::printf("row %zu at %.2f m: rated %.1f t (published %.0f t), tipping at %.1f t\n", row + 1,
                s.row_reach_m[row], rated_t, published_t[row],
                tipping_load_kg(s, s.row_reach_m[row]) / 1000.0);
  }
  // the 1st row is the structure's rating, not its stability's
  EXPECT_GT(tipping_load_kg(s, s.row_reach_m[0]) / s.stability_margin, s.rated_limit_kg);
  // the indicator: at the chart 1, warning from 0.9
  EXPECT_NEAR(load_moment_share(s, s.row_reach_m[1], rated_load_kg(s, s.row_reach_m[1])), 1.0, 1e-12);
  EXPECT_LT(load_moment_share(s, s.row_reach_m[2], 13000.0), s.warn_from);
  EXPECT_GT(load_moment_share(s, s.row_reach_m[2], 14000.0), s.warn_from);
}

// The shipped machine on its tyres (ODE body, the shared wheeled chassis, brakes on), the boom's and
// spreader's weights on it where the statics puts them, and a load at the boom's head `reach_m` ahead of the
// front axle growing at `rate_kg_s`: the load at which the rear axle's tyres leave the ground.
double load_lifting_the_rear_axle_kg(const ReachStackerSettings& s, double reach_m, double rate_kg_s) {
  physics::WorldSettings settings;
  physics::PhysicsWorld world(settings);
  physics::BoxSettings box;
  box.mass_kg = s.mass_kg;
  box.half_extents_m = s.half_extents_m;
  box.collides = false;
  box.pose.position = {0, 0, s.chassis.tyre.radius_m - s.chassis.axles.front().hub_z_m};
  const physics::BodyId body = world.add_box(box);
  WheeledChassis chassis(s.chassis, body);
  const double front = tipping_axle_x_m(s);
  const AxleSettings* rear = &s.chassis.axles.front();
  for (const AxleSettings& a : s.chassis.axles)
    if (a.x_m < rear->x_m) rear = &a;
  const core::Vec3 head{front + reach_m, 0.0, 3.0}, boom_centre = (s.boom_pivot_m + head) * 0.5;
  // settle with the boom and spreader on, then load it
  double load_kg = 0.0;
  for (int k = 0; k < 600000; ++k) {
    const double t = k * kDt;
    if (t > 3.0) load_kg += rate_kg_s * kDt;
    const core::Pose pose = world.pose(body);
    chassis.step(world, {0.0, false, 1.0, 0.0}, FlatGround());
    world.add_force_at(body, pose.to_parent(boom_centre), {0, 0, -s.boom_mass_kg * kG});
    world.add_force_at(body, pose.to_parent(head), {0, 0, -(s.spreader_mass_kg + load_kg) * kG});
    world.step(kDt);
    const core::Pose now = world.pose(body);
    const bool lifted = now.to_parent({rear->x_m, 0.0, rear->hub_z_m}).z - s.chassis.tyre.radius_m > 0.0;
    if (lifted) return load_kg;
  }
  return -1.0;
}

TEST(ReachStacker, TheMultibodyModelTipsAtTheStaticsThreshold) {
  // the load growing slowly (0.5 t/s, quasi-static) until the steer axle lifts: the statics of the support
  // polygon's front edge within 5 %
  const ReachStackerSettings s = shipped();
  for (const double reach : {s.row_reach_m[1], s.row_reach_m[2]}) {
    const double statics = tipping_load_kg(s, reach);
    const double multibody = load_lifting_the_rear_axle_kg(s, reach, 500.0);
    EXPECT_NEAR(multibody, statics, 0.05 * statics) << "at " << reach << " m";
    std::printf("at %.2f m: the steer axle lifts at %.2f t, statics %.2f t\n", reach, multibody / 1000.0,
                statics / 1000.0);
  }
}

TEST(ReachStacker, BadFilesNameTheField) {
  const auto error = [](const std::string& from, const std::string& to) {
    std::string text;
    {
      std::ifstream in(HARBOUR_DATA_DIR "/machines/reach_stacker.yaml");
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    try {
      io::load_reach_stacker(io::YamlFile::parse(text, "reach_stacker.yaml"));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  EXPECT_EQ(error("name: drg450_class", "name: drg450_class"), "loaded");
  std::string e = error("row_reach_m: [2.57, 5.42, 8.27]", "row_reach_m: [2.57, 8.27, 5.42]");
  EXPECT_NE(e.find("machine.load_chart.row_reach_m[2]"), std::string::npos) << e;
  EXPECT_NE(e.find("further out"), std::string::npos) << e;
  e = error("mass_kg: 47700", "mass_kg: 4770");
  EXPECT_NE(e.find("tips over with nothing on it"), std::string::npos) << e;
  e = error("stability_margin: 1.29", "stability_margin: 0.9");
  EXPECT_NE(e.find("machine.load_chart.stability_margin"), std::string::npos) << e;
  e = error("lift: {min_deg: 0, max_deg: 60", "lift: {min_deg: 0, max_deg: 85");
  EXPECT_NE(e.find("machine.boom.lift"), std::string::npos) << e;
  e = error("mass_kg: 6000", "mass_kg: 7900");
  EXPECT_NE(e.find("machine.spreader.mass_kg"), std::string::npos) << e;
  e = error("{label: telescope, kind: axis", "{label: telescopes, kind: axis");
  EXPECT_NE(e.find("telescope"), std::string::npos) << e;
}

// The stacking exercise with its box's mass changed, run by the autopilot until it carries the box.
struct Carrying {
  std::unique_ptr<Simulation> sim;
  const ReachStacker* machine = nullptr;
  std::unique_ptr<Evaluator> evaluator;
};
Carrying carry_box_of(double mass_kg) {
  ExerciseSettings e = io::load_exercise(HARBOUR_DATA_DIR "/exercises/reach_stacker_stack.yaml");
  e.scenario.containers[0].gross_mass_kg = mass_kg;
  Carrying c{std::make_unique<Simulation>(e.scenario)};
  c.machine = &dynamic_cast<const ReachStacker&>(c.sim->machine());
  c.evaluator = std::make_unique<Evaluator>(e);
  const std::unique_ptr<Pilot> pilot = make_pilot(e);
  while (std::string(pilot->activity()) != "carry" && c.sim->time_s() < 60.0) {
    const scene::Controls controls = pilot->next(*c.sim);
    c.sim->step(controls);
    c.evaluator->observe(*c.sim, controls);
  }
  EXPECT_TRUE(c.machine->held_item().has_value());
  return c;
}

// Holds the brakes and works one lever for `seconds` (the others neutral), or until `stop` says so.
template <typename Stop>
void work(Carrying& carrying, const char* lever, double value, double seconds, Stop stop) {
  Simulation& sim = *carrying.sim;
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = table.neutral();
  c.value[static_cast<std::size_t>(table.find("brake"))] = 1.0;
  c.value[static_cast<std::size_t>(table.find(lever))] = value;
  for (const double end = sim.time_s() + seconds; sim.time_s() < end && !stop();) {
    sim.step(c);
    carrying.evaluator->observe(sim, c);
  }
  ASSERT_FALSE(sim.diverged()) << sim.divergence();
}

TEST(ReachStacker, ItsLoadMomentIndicatorReadsTheBoxOnItsHeadPin) {
  // the low-passed load on the head pin beyond the spreader, the box hanging still: its mass
  Carrying c = carry_box_of(24000.0);
  work(c, "boom", 0.0, 5.0, [] { return false; });
  EXPECT_NEAR(c.machine->measured_load_kg(), 24000.0, 0.01 * 24000.0);
  EXPECT_NEAR(c.machine->load_moment_share(),
              24000.0 / rated_load_kg(c.machine->settings(), c.machine->reach_m()), 0.01);
}

TEST(ReachStacker, TheLimiterStopsTheTelescopeAtTheChartAndWithItsFaultTheMachineTips) {
  // 30 t extended from the first row outward: the chart's rating falls to 30 t between the first and second
  // rows, where the limiter stops the extension; with the limiter failed the extension goes on until the
  // steer axle lifts where the statics of the front axle balance 30 t, and the machine tips over
  constexpr double kBox_kg = 30000.0;
  {
    Carrying c = carry_box_of(kBox_kg);
    const ReachStacker& m = *c.machine;
    work(c, "telescope", 0.3, 40.0, [] { return false; });
    EXPECT_TRUE(m.limiter_stopping());
    EXPECT_EQ(m.tally().limiter_trips, 1u);
    // the attempt counts the trip, stores it and its rubric deducts it (it was counted for a grab's bulk
    // only)
    const Metrics& metrics = c.evaluator->metrics();
    EXPECT_EQ(metrics.limiter_trips, 1);
    const auto rows = metrics.rows();
    const auto stored =
        std::find_if(rows.begin(), rows.end(), [](const auto& r) { return r.first == "limiter_trips"; });
    ASSERT_NE(stored, rows.end());
    EXPECT_EQ(stored->second, 1.0);
    const Score score = c.evaluator->score();
    EXPECT_TRUE(std::any_of(score.deductions.begin(), score.deductions.end(), [](const Score::Deduction& d) {
      return d.reason == "load-moment limiter trip" && d.count == 1 && d.points > 0.0;
    }));
    EXPECT_EQ(m.tip_overs(), 0u);
    const double rated_kg = rated_load_kg(m.settings(), m.reach_m());
    EXPECT_NEAR(rated_kg, kBox_kg, 0.03 * kBox_kg);  // stopped at the chart
    EXPECT_LT(m.tilt_rad(), 0.02);
    std::printf("30 t: the limiter stopped the telescope at %.2f m reach (chart %.1f t there)\n", m.reach_m(),
                rated_kg / 1000.0);
  }
  {
    Carrying c = carry_box_of(kBox_kg);
    const ReachStacker& m = *c.machine;
    c.sim->command({InstructorCommand::Kind::kLimiterFault});
    const AxleSettings& rear = m.settings().chassis.axles.back();
    const auto rear_lifted = [&] {
      const core::Vec3 hub = c.sim->world().pose(m.body()).to_parent({rear.x_m, 0.0, rear.hub_z_m});
      return hub.z - m.settings().chassis.tyre.radius_m > 0.0;
    };
    work(c, "telescope", 0.3, 40.0, rear_lifted);
    ASSERT_TRUE(rear_lifted());
    const double statics_kg = tipping_load_kg(m.settings(), m.reach_m());
    EXPECT_NEAR(statics_kg, kBox_kg, 0.05 * kBox_kg);
    std::printf(
        "30 t, limiter failed: the steer axle lifted at %.2f m reach, where the statics tip at %.1f t\n",
        m.reach_m(), statics_kg / 1000.0);
    work(c, "telescope", 0.3, 15.0, [] { return false; });
    EXPECT_GE(m.tip_overs(), 1u);
    // the evaluation counts it, 50 points off safety
    EXPECT_EQ(c.evaluator->metrics().tip_overs, static_cast<int>(m.tip_overs()));
    bool deducted = false;
    for (const Score::Deduction& d : c.evaluator->score().deductions)
      deducted |= d.reason == "tip-over" && d.points == 50.0 * d.count && d.skill == Skill::kSafety;
    EXPECT_TRUE(deducted);
  }
}

TEST(ReachStacker, AtFullLockItTurnsOnTheAckermannCircleAboutItsFrontAxle) {
  // rear-wheel steering: the turn's centre on the front (drive) axle's line, its centre at L / tan δ from it
  Simulation sim(io::load_exercise(HARBOUR_DATA_DIR "/exercises/reach_stacker_free_practice.yaml").scenario);
  const auto& m = dynamic_cast<const ReachStacker&>(sim.machine());
  const scene::ControlTable& table = sim.control_table();
  scene::Controls c = table.neutral();
  c.value[static_cast<std::size_t>(table.find("direction"))] = 2.0;
  c.value[static_cast<std::size_t>(table.find("steer"))] = 1.0;
  for (int k = 0; k < static_cast<int>(20.0 / Simulation::kStep_s); ++k) {
    c.value[static_cast<std::size_t>(table.find("throttle"))] =
        std::clamp(0.3 * (1.0 - m.forward_mps()), 0.0, 1.0);
    sim.step(c);
  }
  const ReachStackerSettings& s = m.settings();
  const double front = tipping_axle_x_m(s);
  const double expected = m.chassis().steer_base_m() / std::tan(s.chassis.max_steer_rad);
  const core::Vec3 v = sim.world().point_velocity(m.body(), {front, 0, 0});
  const double radius = std::hypot(v.x, v.y) / std::abs(sim.world().angular_velocity(m.body()).z);
  EXPECT_NEAR(radius, expected, 0.05 * expected);
  std::printf("reach stacker at full lock: %.3f m against L / tan(delta) = %.3f m\n", radius, expected);
}

TEST(ReachStacker, TheAutopilotStacksTheBoxThreeHighInTheSecondRowAndAKeyframeContinuesExactly) {
  const ExerciseSettings e = io::load_exercise(HARBOUR_DATA_DIR "/exercises/reach_stacker_stack.yaml");
  Simulation sim(e.scenario);
  const std::unique_ptr<Pilot> pilot = make_pilot(e);
  Evaluator evaluator(e);
  std::vector<std::uint8_t> keyframe;  // taken while it reaches out over the stacks
  std::vector<scene::Controls> after;
  std::uint64_t hash_after = 0;
  while (!evaluator.finished() && sim.time_s() < e.rules.time_limit_s) {
    const scene::Controls c = pilot->next(sim);
    if (sim.time_s() >= 60.0 && keyframe.empty()) keyframe = sim.save_state();
    if (!keyframe.empty() && after.size() < 2000) after.push_back(c);
    sim.step(c);
    if (after.size() == 2000 && hash_after == 0) hash_after = sim.state_hash();
    evaluator.observe(sim, c);
  }
  const Metrics& m = evaluator.metrics();
  EXPECT_EQ(m.moves_completed, 1);
  ASSERT_EQ(m.placement_offset_m.size(), 1u);
  EXPECT_LT(m.placement_offset_m[0], 0.05);  // on the box below
  EXPECT_EQ(m.collisions, 0);
  EXPECT_GE(evaluator.score().total, 90.0);
  std::printf("stacked three high in the second row in %.1f s, %.3f m off, score %.0f\n", m.time_s,
              m.placement_offset_m[0], evaluator.score().total);
  // a keyframe taken on the way continues bit for bit
  ASSERT_EQ(after.size(), 2000u);
  Simulation again(e.scenario);
  again.restore_state(keyframe);
  for (const scene::Controls& c : after)
    again.step(c);
  EXPECT_EQ(again.state_hash(), hash_after);
}

TEST(ReachStacker, TheAutopilotTakesTheTrucksBoxThroughTheSlalomAndABadDriverHitsAPost) {
  // the box comes off the truck, the truck drives off, the box goes laden round three posts on the lane's
  // line and down square on its mark; a driver who ignores the route drives it into the first post
  const ExerciseSettings e = io::load_exercise(HARBOUR_DATA_DIR "/exercises/reach_stacker_truck_slalom.yaml");
  const auto attempt = [&](DriverDefects defects) {
    Simulation sim(e.scenario);
    ReachStackerAutopilot pilot(e, defects);
    Evaluator evaluator(e);
    while (!evaluator.finished() && sim.time_s() < e.rules.time_limit_s && !sim.diverged()) {
      const scene::Controls c = pilot.next(sim);
      sim.step(c);
      evaluator.observe(sim, c);
    }
    EXPECT_FALSE(sim.diverged()) << sim.divergence();
    return std::pair{evaluator.metrics(), evaluator.score().total};
  };
  const auto [good, good_score] = attempt({});
  ASSERT_EQ(good.moves_completed, 1);
  std::printf("slalom: %.1f s, placed %.3f m off, %.2f deg skew, %d collisions, score %.0f\n", good.time_s,
              good.placement_offset_m.at(0), good.placement_skew_deg.at(0), good.collisions, good_score);
  EXPECT_LT(good.placement_offset_m[0], 0.1);
  EXPECT_EQ(good.collisions, 0);
  EXPECT_EQ(good.hard_landings, 0);
  EXPECT_EQ(good.tip_overs, 0);
  EXPECT_GE(good_score, e.rules.pass_score);

  const auto [bad, bad_score] = attempt({.ignore_route = true});
  std::printf("straight through: %d collisions (%d with boxes), %d moves, score %.0f\n", bad.collisions,
              bad.container_collisions, bad.moves_completed, bad_score);
  EXPECT_GE(bad.container_collisions, 1);
  EXPECT_LE(bad_score, good_score - e.rules.points_collision);
}

}  // namespace
}  // namespace harbour::sim
