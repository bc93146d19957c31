#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "harbour/io/BulkFiles.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/sim/Evaluation.h"
#include "scenes/MhcScenes.h"

namespace harbour::sim {
namespace {

constexpr double kG = 9.80665;

scene::Controls mhc_controls(const Simulation& sim,
                             std::initializer_list<std::pair<const char*, double>> values) {
  scene::Controls c = sim.control_table().neutral();
  for (const auto& [label, value] : values)
    c.value[static_cast<std::size_t>(sim.control_table().find(label))] = value;
  return c;
}

const MobileHarbourCrane& mhc(const Simulation& sim) {
  return dynamic_cast<const MobileHarbourCrane&>(sim.machine());
}

// The statics tests damp the ropes' stretching more (it changes no static force) so the start's bounce (the
// ropes are built unstretched) dies out in seconds. It damps the rope running over the sheaves as much: the
// grab's closing ropes, on parts about a metre long, then never settle (the tests that need them run as
// built).
ScenarioSettings damped(ScenarioSettings s) {
  auto& crane = s.machine.as<MhcSetup>().crane;
  for (cable::ReevingSettings* reeving : {&crane.luffing, &crane.hoist})
    for (cable::RopeSettings& rope : reeving->ropes)
      rope.axial_damping_s = 0.05;
  return s;
}

void run(Simulation& sim, double seconds, const scene::Controls& controls) {
  for (int k = 0; k < static_cast<int>(std::lround(seconds / Simulation::kStep_s)); ++k)
    sim.step(controls);
  ASSERT_FALSE(sim.diverged()) << sim.divergence();
}

// a rope segment's ends in the world
std::array<core::Vec3, 2> ends(const cable::HoistSystem& ropes, int rope, int segment) {
  std::array<core::Vec3, 2> e;
  ropes.polyline(rope, segment, e);
  return e;
}

TEST(Mhc, TheLuffingRopesCarryTheBoomsStaticMoment) {
  // about the boom's foot: the boom's weight, the hoist ropes' pulls at the head and the ropes' own weight
  // (half of each fall at its boom end) balance the luffing falls' pulls: predict their tension from that
  Simulation sim(damped(scenes::mhc_on_quay(HARBOUR_DATA_DIR)));
  const scene::Controls neutral = sim.control_table().neutral();
  run(sim, 15.0, neutral);
  const MobileHarbourCrane& m = mhc(sim);
  const MhcSettings& settings = m.settings();
  const auto balance = [&] {
    const core::Pose house = sim.world().pose(m.house_body());
    const core::Vec3 foot = house.to_parent(settings.house_com_m * -1.0 + settings.boom_foot_m);
    const core::Vec3 axis = house.rotation * core::Vec3{0, 1, 0};
    const auto moment = [&](const core::Vec3& at, const core::Vec3& force) {
      return dot(cross(at - foot, force), axis);
    };
    // pulls of the segments with an end on the boom (reeving body 1), towards their other end
    const auto pulls_on_boom = [&](const cable::HoistSystem& ropes, const cable::ReevingSettings& reeving,
                                   bool with_tension, double& arm_sum) {
      double sum = 0.0;
      for (int r = 0; r < ropes.rope_count(); ++r) {
        const std::vector<int>& path = reeving.ropes[static_cast<std::size_t>(r)].path;
        for (int g = 0; g < ropes.segment_count(r); ++g) {
          const int a =
              reeving.elements[static_cast<std::size_t>(path[static_cast<std::size_t>(g)])].mount.body;
          const int b =
              reeving.elements[static_cast<std::size_t>(path[static_cast<std::size_t>(g) + 1])].mount.body;
          if ((a == 1) == (b == 1)) continue;
          const auto [end_a, end_b] = ends(ropes, r, g);
          const core::Vec3 on_boom = a == 1 ? end_a : end_b, other = a == 1 ? end_b : end_a;
          const core::Vec3 d = other - on_boom;
          const core::Vec3 u = d * (1.0 / std::sqrt(dot(d, d)));
          const double weight = 0.5 * ropes.unstretched_length(r, g) *
                                reeving.ropes[static_cast<std::size_t>(r)].mass_per_m_kg * kG;
          sum += moment(on_boom, {0, 0, -weight});
          if (with_tension)
            sum += moment(on_boom, u * ropes.tension(r, g));
          else
            arm_sum += moment(on_boom, u);
        }
      }
      return sum;
    };
    double luffing_arms = 0.0, unused = 0.0;
    double other = moment(sim.world().pose(m.boom_body()).position, {0, 0, -settings.boom_mass_kg * kG});
    other += pulls_on_boom(m.hoist(), settings.hoist, true, unused);
    other += pulls_on_boom(m.luffing(), settings.luffing, false, luffing_arms);
    const double predicted = -other / luffing_arms;
    double measured = 0.0;
    const int falls = m.luffing().segment_count(0) - 1;  // the drum's lead to the A-frame is not a fall
    for (int g = 1; g <= falls; ++g)
      measured += m.luffing().tension(0, g) / falls;
    return std::pair{measured, predicted};
  };
  // averaged over 2 s, every step: the ropes' transverse waves swing each instant's end forces by a few %
  double measured = 0.0, predicted = 0.0;
  for (int k = 0; k < 2000; ++k) {
    sim.step(neutral);
    const auto [t, p] = balance();
    measured += t / 2000;
    predicted += p / 2000;
  }
  EXPECT_NEAR(measured, predicted, 0.02 * predicted);
  EXPECT_GT(predicted, 5e4);  // a real load on each of the six falls: the boom and the grab at 35 m
}

TEST(Mhc, OutriggerPadsCarryTheMachinesWeightAndBalanceItsMoment) {
  Simulation sim(scenes::mhc_on_quay(HARBOUR_DATA_DIR));  // as built: see damped()
  run(sim, 15.0, sim.control_table().neutral());
  const MobileHarbourCrane& m = mhc(sim);
  const MhcSettings& settings = m.settings();
  double weight = settings.undercarriage_mass_kg * kG, moment_y = 0.0;
  for (const physics::BodyId body : {m.house_body(), m.boom_body(), m.block_body(), m.grab_lower_body()}) {
    const double w = sim.world().mass_kg(body) * kG;
    weight += w;
    moment_y += w * (sim.world().pose(body).position.x - m.position_m().x);
  }
  // the ropes' weight, each at its segments' middles
  for (const auto& [ropes, reeving] :
       {std::pair{&m.luffing(), &settings.luffing}, std::pair{&m.hoist(), &settings.hoist}})
    for (int r = 0; r < ropes->rope_count(); ++r)
      for (int g = 0; g < ropes->segment_count(r); ++g) {
        const auto [a, b] = ends(*ropes, r, g);
        const double w =
            ropes->unstretched_length(r, g) * reeving->ropes[static_cast<std::size_t>(r)].mass_per_m_kg * kG;
        weight += w;
        moment_y += w * (0.5 * (a.x + b.x) - m.position_m().x);
      }
  const PadForces pads = m.pad_forces_n();
  double sum = 0.0, pad_moment_y = 0.0, pad_moment_x = 0.0;
  const double sx[] = {1, -1, -1, 1}, sy[] = {1, 1, -1, -1};
  for (std::size_t i = 0; i < 4; ++i) {
    sum += pads[i];
    pad_moment_y += pads[i] * sx[i] * settings.pad_half_spread_x_m;
    pad_moment_x += pads[i] * sy[i] * settings.pad_half_spread_y_m;
  }
  EXPECT_NEAR(sum, weight, 0.002 * weight);
  EXPECT_NEAR(pad_moment_y, moment_y, 0.01 * std::abs(moment_y));
  EXPECT_NEAR(pad_moment_x, 0.0, 0.002 * std::abs(moment_y));  // the boom points along x
  // the boom side's pads carry more, none lifts off
  EXPECT_GT(pads[0], pads[1]);
  EXPECT_GT(*std::min_element(pads.begin(), pads.end()), 0.0);
  EXPECT_EQ(m.pad_lift_offs(), 0u);
}

TEST(Mhc, PadForcesShareALoadAndMomentByTheRigidPlane) {
  // 1000 kN down, 2000 kN m about +y (the +x side pressed) on pads at +-5, +-4
  const PadForces f = pad_forces(1e6, {0.0, 2e6, 0.0}, 5.0, 4.0, 0.0);
  EXPECT_NEAR(f[0], 250e3 + 5.0 * 2e6 / 100.0, 1e-6);
  EXPECT_NEAR(f[1], 250e3 - 5.0 * 2e6 / 100.0, 1e-6);
  EXPECT_NEAR(f[2], f[1], 1e-6);
  EXPECT_NEAR(f[3], f[0], 1e-6);
}

TEST(Mhc, SlewTorqueAcceleratesTheHouseAndBoomByTheirInertia) {
  ScenarioSettings s = damped(scenes::mhc_on_quay(HARBOUR_DATA_DIR));
  MhcSettings& settings = s.machine.as<MhcSetup>().crane;
  settings.slew_drive.max_force_n = 1.0e6;  // [N m]: the motor saturates under the steep reference ramp
  settings.slew_drive.acceleration_mps2 = 1.0;
  // light ropes: the check is of the house and boom's inertia (the ropes' mass turns with them too)
  for (cable::ReevingSettings* reeving : {&settings.luffing, &settings.hoist})
    for (cable::RopeSettings& rope : reeving->ropes)
      rope.mass_per_m_kg *= 0.01;
  Simulation sim(s);
  run(sim, 10.0, sim.control_table().neutral());
  const MobileHarbourCrane& m = mhc(sim);
  // the mean acceleration over 1 s (the rate carries a small 10 Hz ripple), and the mean torque the grab's
  // ropes put on the boom head about the axis as the grab lags behind
  const scene::Controls slew = mhc_controls(sim, {{"slew", 1.0}});
  run(sim, 0.02, slew);
  const double rate_0 = sim.world().hinge_rate(m.slew_hinge());
  double rope_torque = 0;
  const int n = 1000;
  for (int k = 0; k < n; ++k) {
    sim.step(slew);
    for (int r = 0; r < m.hoist().rope_count(); ++r) {
      const auto [top, bottom] = ends(m.hoist(), r, 1);  // boom head down to the grab
      const core::Vec3 u = (bottom - top) * (1.0 / std::sqrt(dot(bottom - top, bottom - top)));
      rope_torque += cross(top - m.position_m(), u * m.hoist().tension(r, 1)).z / n;
    }
  }
  const double measured = (sim.world().hinge_rate(m.slew_hinge()) - rate_0) / (n * Simulation::kStep_s);
  // the inertia about the slewing axis: each body's own (its box about its centre, turned into the world)
  // plus its mass at its distance from the axis (the grab hangs on its ropes: it shares through their pull)
  double inertia = 0.0;
  for (const auto& [body, half] :
       {std::pair{m.house_body(), settings.house_half_extents_m},
        std::pair{m.boom_body(), core::Vec3{0.5 * settings.boom_length_m, settings.boom_half_width_m,
                                            settings.boom_half_width_m}}}) {
    const double mass = sim.world().mass_kg(body);
    const core::Vec3 own{mass / 3 * (half.y * half.y + half.z * half.z),
                         mass / 3 * (half.x * half.x + half.z * half.z),
                         mass / 3 * (half.x * half.x + half.y * half.y)};
    const core::Pose p = sim.world().pose(body);
    for (int k = 0; k < 3; ++k)
      inertia += p.rotation.m[2][k] * p.rotation.m[2][k] * (k == 0 ? own.x : k == 1 ? own.y : own.z);
    const double dx = p.position.x - m.position_m().x, dy = p.position.y - m.position_m().y;
    inertia += mass * (dx * dx + dy * dy);
  }
  const double expected = (1.0e6 + rope_torque) / inertia;
  EXPECT_NEAR(measured, expected, 0.02 * expected);
  EXPECT_LT(rope_torque, 0.0);  // the grab holds the head back
  EXPECT_NEAR(sim.world().hinge_torque(m.slew_hinge()), 1.0e6, 1e3);
}

TEST(Mhc, TheGrabSwingsAcrossTheBoomWithThePendulumsPeriod) {
  // across the boom the two holding ropes hang parallel: the open grab (its closing ropes slack) swings as
  // a point on a string as long as they are
  Simulation sim(damped(scenes::mhc_on_quay(HARBOUR_DATA_DIR)));
  const scene::Controls neutral = sim.control_table().neutral();
  run(sim, 10.0, neutral);
  const MobileHarbourCrane& m = mhc(sim);
  auto& world = const_cast<physics::PhysicsWorld&>(sim.world());
  for (const physics::BodyId b : {m.block_body(), m.grab_lower_body()})
    world.set_linear_velocity(b, {0.0, 0.3, 0.0});
  const auto [sheave, anchor] = ends(m.hoist(), 0, 1);  // holding rope 1: boom head sheave to the grab
  const double length = std::sqrt(dot(anchor - sheave, anchor - sheave));
  std::vector<double> crossings;
  double last = sim.world().pose(m.block_body()).position.y - m.boom_head_m().y;
  for (int k = 0; k < 40000 && crossings.size() < 7; ++k) {
    sim.step(neutral);
    const double y = sim.world().pose(m.block_body()).position.y - m.boom_head_m().y;
    if ((last < 0.0) != (y < 0.0)) crossings.push_back(sim.time_s());
    last = y;
  }
  ASSERT_EQ(crossings.size(), 7u);
  const double period = (crossings[6] - crossings[0]) / 3.0;
  const double expected = 2 * std::numbers::pi * std::sqrt(length / kG);
  EXPECT_NEAR(period, expected, 0.02 * expected);
}

TEST(Mhc, TheGrabShutsWhenTheClosingRopesReelInAndOpensWhenTheyPayOut) {
  Simulation sim(scenes::mhc_on_quay(HARBOUR_DATA_DIR));  // as built: see damped()
  run(sim, 5.0, sim.control_table().neutral());
  const MobileHarbourCrane& m = mhc(sim);
  EXPECT_GT(m.grab_opening(), 0.95);
  const double head_z = sim.world().pose(m.block_body()).position.z;
  run(sim, 6.0, mhc_controls(sim, {{"grab", 1.0}}));
  run(sim, 2.0, sim.control_table().neutral());
  EXPECT_LT(m.grab_opening(), 0.05);
  // the holding winch stood and the closing winch stopped on the shut switch: the head stays where it hung
  // (the ropes stretch a little under the shells' weight moving onto the closing ropes)
  EXPECT_NEAR(sim.world().pose(m.block_body()).position.z, head_z, 0.15);
  run(sim, 6.0, mhc_controls(sim, {{"grab", -1.0}}));
  run(sim, 2.0, sim.control_table().neutral());
  EXPECT_GT(m.grab_opening(), 0.95);
}

// 40 t shells (about 44 t under the head) at 35 m: the chart allows 57 t there and 44.5 t at 44.6 m (the grab
// hangs high: luffing out lowers the head by some 13 m)
ScenarioSettings heavy_grab_hanging_high() {
  ScenarioSettings s = damped(scenes::mhc_on_quay(HARBOUR_DATA_DIR));
  s.machine.as<MhcSetup>().crane.grab_lower_mass_kg = 40000.0;
  s.machine.as<MhcSetup>().start.hanging_z_m = 38.0;
  return s;
}

TEST(Mhc, TheLoadMomentLimiterStopsLuffingOutBeforeTheChartIsExceeded) {
  Simulation sim(heavy_grab_hanging_high());
  run(sim, 10.0, sim.control_table().neutral());
  const MobileHarbourCrane& m = mhc(sim);
  EXPECT_LT(m.utilisation(), 0.85);
  const scene::Controls luff_out = mhc_controls(sim, {{"luff", -1.0}});
  double worst = 0.0;
  for (int k = 0; k < 60000; ++k) {
    sim.step(luff_out);
    worst = std::max(worst, m.utilisation());
  }
  const double angle = m.boom_angle_rad();
  run(sim, 5.0, luff_out);
  EXPECT_NEAR(m.boom_angle_rad(), angle, 1e-3);  // stopped, though the lever is held out
  EXPECT_GT(m.boom_angle_rad(), m.settings().boom_min_angle_rad + 0.05);  // by the limiter, not the switch
  EXPECT_GT(worst, 0.97);
  EXPECT_LT(worst, 1.02);
  EXPECT_EQ(m.limiter_trips(), 1u);
  // luffing in (reducing the moment) is allowed at once
  run(sim, 3.0, mhc_controls(sim, {{"luff", 1.0}}));
  EXPECT_GT(m.boom_angle_rad(), angle + 0.01);
}

// The instructor's limiter fault: the same luff out goes on past the chart, the limiter still warning (its
// stop lamp and the fault lamp lit, the trip counted) but cutting nothing, until the boom's own switch; the
// fault cleared, luffing out is cut again at once.
TEST(Mhc, WithItsLimiterFailedTheBoomLuffsOutPastTheChart) {
  Simulation sim(heavy_grab_hanging_high());
  run(sim, 10.0, sim.control_table().neutral());
  const MobileHarbourCrane& m = mhc(sim);
  sim.command({InstructorCommand::Kind::kLimiterFault});
  run(sim, 0.01, sim.control_table().neutral());
  EXPECT_TRUE(m.fault_active(MachineFault::kLoadMomentLimiter));
  const scene::Controls luff_out = mhc_controls(sim, {{"luff", -1.0}});
  double worst = 0.0;
  for (int k = 0; k < 90000; ++k) {
    sim.step(luff_out);
    worst = std::max(worst, m.utilisation());
  }
  EXPECT_GT(worst, 1.1);  // past the chart: the limiter cut nothing
  // on to the boom's lowest angle, where its own limit switch stops it
  EXPECT_NEAR(m.boom_angle_rad(), m.settings().boom_min_angle_rad, 0.01);
  std::printf("limiter failed: luffed out to %.1f m radius (boom %.1f deg)\n", m.radius_m(),
              m.boom_angle_rad() * 180.0 / std::numbers::pi);
  EXPECT_EQ(m.limiter_trips(), 1u);
  const std::vector<std::string> names = sim.scene().indicators;
  const auto reading = [&](const char* name) {
    const auto at = std::find(names.begin(), names.end(), name);
    return at == names.end() ? -1.0
                             : sim.snapshot()->indicators[static_cast<std::size_t>(at - names.begin())];
  };
  EXPECT_EQ(reading("lamp_limiter_fault"), 1.0);
  EXPECT_EQ(reading("limiter_stop"), 1.0);  // it still warns
  sim.command({InstructorCommand::Kind::kClearFaults});
  run(sim, 0.5, luff_out);
  const double angle = m.boom_angle_rad();
  run(sim, 3.0, luff_out);
  EXPECT_NEAR(m.boom_angle_rad(), angle, 1e-3);  // cut again, the lever still out
  EXPECT_EQ(reading("lamp_limiter_fault"), 0.0);
}

// Luffed in and hoisted up with the levers held: the boom stops on its upper angle switch and the grab on its
// upper hoist switch, each counted once in the machine's tally (what the evaluator scores as limit hits).
TEST(Mhc, TheBoomAndTheGrabStopOnTheirLimitSwitchesAndCountEachHitOnce) {
  Simulation sim(damped(scenes::mhc_on_quay(HARBOUR_DATA_DIR)));
  run(sim, 2.0, sim.control_table().neutral());
  const MobileHarbourCrane& m = mhc(sim);
  EXPECT_EQ(m.tally().limit_hits, 0u);
  run(sim, 90.0, mhc_controls(sim, {{"luff", 1.0}}));
  EXPECT_NEAR(m.boom_angle_rad(), m.settings().boom_max_angle_rad, 0.01);
  EXPECT_EQ(m.tally().limit_hits, 1u);
  run(sim, 90.0, mhc_controls(sim, {{"hoist", 1.0}}));
  // the stop overshoots on the ropes' stretch (0.105 m measured)
  EXPECT_NEAR(sim.world().pose(m.block_body()).position.z, m.settings().hoist_upper_limit_m, 0.15);
  EXPECT_EQ(m.tally().limit_hits, 2u);
}

TEST(Mhc, StepsAreAPureFunctionOfTheInputsAndKeyframesContinueBitForBit) {
  const ScenarioSettings s = scenes::mhc_on_quay(HARBOUR_DATA_DIR);
  const auto script = [](const Simulation& sim, std::int64_t step) {
    const double t = static_cast<double>(step) * Simulation::kStep_s;
    return mhc_controls(sim, {{"slew", t < 1.0 ? 0.8 : 0.0},
                              {"luff", t < 2.0 ? -0.5 : 0.3},
                              {"hoist", t > 1.5 ? -0.6 : 0.0},
                              {"grab", t > 2.5 ? 1.0 : 0.0}});
  };
  Simulation a(s), b(s);
  std::vector<std::uint8_t> keyframe;
  for (std::int64_t k = 0; k < 3000; ++k) {
    if (k == 1500) keyframe = a.save_state();
    a.step(script(a, k));
    b.step(script(b, k));
  }
  EXPECT_EQ(a.state_hash(), b.state_hash());
  Simulation c(s);
  c.restore_state(keyframe);
  for (std::int64_t k = 1500; k < 3000; ++k)
    c.step(script(c, k));
  EXPECT_EQ(c.state_hash(), a.state_hash());
  EXPECT_NE(mhc(a).slew_rad(), 0.0);
}

TEST(Mhc, AnInstructorFaultTheMachineLacksIsRefusedWithoutChange) {
  Simulation sim(scenes::mhc_on_quay(HARBOUR_DATA_DIR));
  const std::uint64_t before = sim.state_hash();
  InstructorCommand c;
  c.kind = InstructorCommand::Kind::kLandedSensorFault;
  EXPECT_THROW(sim.command(c), std::invalid_argument);
  EXPECT_EQ(sim.state_hash(), before);
  EXPECT_THROW(static_cast<void>(sim.machine_as<StsCrane>()), std::logic_error);
  EXPECT_EQ(sim.scene().machine, "mhc");
}

TEST(Mhc, AFreePracticeIsEvaluatedOnWhatEveryMachineShows) {
  // the grab lowered at full speed onto the quay is a collision; an emergency stop is counted; without goals
  // the practice runs to its time limit
  const ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_free_practice.yaml");
  Simulation sim(exercise.scenario);
  Evaluator evaluator(exercise);
  const auto observed = [&](const scene::Controls& controls, int steps, auto until) {
    for (int k = 0; k < steps && !until(); ++k) {
      sim.step(controls);
      evaluator.observe(sim, controls);
    }
  };
  observed(mhc_controls(sim, {{"hoist", -1.0}}), 20000, [&] { return evaluator.metrics().collisions > 0; });
  EXPECT_EQ(evaluator.metrics().collisions, 1);
  EXPECT_LT(mhc(sim).attachment_bottom_z_m(), 0.3);  // on the quay
  // a faulty device's reading (not a number) is a released button, to the machine and to the evaluation
  observed(mhc_controls(sim, {{"emergency_stop", std::nan("")}}), 100, [] { return false; });
  EXPECT_EQ(evaluator.metrics().emergency_stops, 0);
  observed(mhc_controls(sim, {{"emergency_stop", 1.0}}), 100, [] { return false; });
  EXPECT_EQ(evaluator.metrics().emergency_stops, 1);
  EXPECT_FALSE(evaluator.finished());
  const Score score = evaluator.score();
  EXPECT_NEAR(score.total, 100.0 - exercise.rules.points_collision - exercise.rules.points_emergency_stop,
              1e-9);
}

TEST(Mhc, TheExercisesBulkMaterialIsInTheStateAndItsKeyframes) {
  const ExerciseSettings exercise = io::load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_free_practice.yaml");
  ASSERT_TRUE(exercise.scenario.bulk.has_value());
  Simulation a(exercise.scenario);
  ASSERT_NE(a.bulk(), nullptr);
  const bulk::VolumeBalance start = a.bulk()->balance();
  EXPECT_NEAR(start.in_grids_m3, 250.0, 0.05 * 250.0);  // a relaxed cone of about the volume asked for
  const scene::Controls slew = mhc_controls(a, {{"slew", 1.0}});
  for (int k = 0; k < 500; ++k)
    a.step(slew);
  const std::vector<std::uint8_t> keyframe = a.save_state();
  Simulation b(exercise.scenario);
  b.restore_state(keyframe);
  for (int k = 0; k < 500; ++k) {
    a.step(slew);
    b.step(slew);
  }
  EXPECT_EQ(a.state_hash(), b.state_hash());
  EXPECT_NEAR(a.bulk()->balance().discrepancy_m3(), 0.0, 1e-9);
  // the same crane without the pile is another scenario: its keyframes do not mix
  ScenarioSettings bare = exercise.scenario;
  bare.bulk.reset();
  Simulation c(bare);
  EXPECT_THROW(c.restore_state(keyframe), core::StateError);
  EXPECT_NE(c.state_hash(), Simulation(exercise.scenario).state_hash());
}

// The MHC with a coal heap right under its grab (20 m x 20 m of 10 cm cells).
ScenarioSettings mhc_over_a_heap() {
  ScenarioSettings s = scenes::mhc_on_quay(HARBOUR_DATA_DIR);
  bulk::BulkScene scene;
  const auto materials = io::load_materials(HARBOUR_DATA_DIR "/materials.yaml");
  for (const bulk::Material& m : materials)
    if (m.name == "coal") scene.material = m;
  scene.spill_level_m = -3.5;
  bulk::GridPlacement yard;
  yard.name = "yard";
  yard.settings = {200, 200, 0.1};
  yard.origin_x_m = 25.5;
  yard.origin_y_m = -10.0;
  scene.grids.push_back(yard);
  scene.heaps.push_back({0, 10.0, 10.0, 150.0});
  s.bulk = scene;
  return s;
}

TEST(Mhc, TheGrabBitesTheHeapAndItsLoadHangsOnTheRopes) {
  Simulation sim(mhc_over_a_heap());
  const MobileHarbourCrane& m = mhc(sim);
  const double empty_kg = m.settings().grab_head_mass_kg + m.settings().grab_lower_mass_kg;
  const double heap_m3 = sim.bulk()->balance().in_grids_m3;
  run(sim, 4.0, sim.control_table().neutral());  // the bite model's jaws open with the shells
  // down onto the heap: the ropes go slack as the shells rest on it
  const scene::Controls lower = mhc_controls(sim, {{"hoist", -0.5}});
  int k = 0;
  for (; k < 30000 && m.hoisted_load_n() > 0.5 * empty_kg * kG; ++k)
    sim.step(lower);
  ASSERT_LT(k, 30000) << "the grab never came to rest on the heap";
  const double resting_z = m.attachment_bottom_z_m();
  EXPECT_GT(resting_z, 1.0);  // on the heap (4 m high), not the quay
  run(sim, 0.5, lower);
  // shut: the holding winch follows, the jaws cut in; the bite is the paper's w W v dt summed over the
  // steps the jaws cut (w the opening as they cut, v the sinking speed)
  const scene::Controls shut = mhc_controls(sim, {{"grab", 1.0}});
  const double cut_before_m3 = sim.bulk()->loaded_m3();
  const bulk::GrabSettings& g = sim.bulk()->grab_settings(sim.bulk_grab());
  double formula_m3 = 0.0;
  for (int n = 0; n < 6000; ++n) {
    const double opening = sim.bulk()->grab(sim.bulk_grab()).opening_m;
    sim.step(shut);
    // the jaws cut for as long as they close at full speed: the step's closing over the full-speed closing
    const double closed = opening - sim.bulk()->grab(sim.bulk_grab()).opening_m;
    if (sim.bulk()->grab(sim.bulk_grab()).digging)
      formula_m3 += opening * g.width_m * g.sinking_speed_mps * closed / (g.max_opening_m / g.closing_time_s);
  }
  const double bite_m3 = sim.bulk()->grab(sim.bulk_grab()).load_m3;
  // a full bite: the jaw tips swing down their arc into the heap and the grab stays down while it shuts
  EXPECT_GT(bite_m3, 0.8 * m.settings().grab.capacity_m3);
  EXPECT_LE(bite_m3, m.settings().grab.capacity_m3 + 1e-9);
  // what the jaws cut is the formula's; what they keep is all but what their jitter on the ropes let fall
  const double cut_m3 = sim.bulk()->loaded_m3() - cut_before_m3;
  EXPECT_NEAR(cut_m3, formula_m3, 0.05 * formula_m3);
  EXPECT_GT(bite_m3, 0.9 * cut_m3);
  EXPECT_LT(m.attachment_bottom_z_m(), resting_z - 0.5);  // it sank into the heap as it cut
  run(sim, 8.0, mhc_controls(sim, {{"hoist", 0.5}}));     // lift it clear
  run(sim, 4.0, sim.control_table().neutral());
  EXPECT_GT(m.attachment_bottom_z_m(), resting_z + 2.0);
  // the bite's weight hangs on the ropes with the grab's (the limiter's filtered load)
  const double bite_kg = sim.bulk()->mass_kg(sim.bulk()->grab(sim.bulk_grab()).load_m3);
  EXPECT_NEAR(m.limiter_load_n() / kG, empty_kg + bite_kg, 0.05 * (empty_kg + bite_kg));
  // nothing lost: heap, grab and anything in the air add up to what was there
  const bulk::VolumeBalance b = sim.bulk()->balance();
  EXPECT_NEAR(b.in_grids_m3 + b.in_grabs_m3 + b.in_flight_m3 + b.spilled_m3, heap_m3, 1e-9 * heap_m3);
  EXPECT_FALSE(sim.diverged());
}

}  // namespace
}  // namespace harbour::sim
