#include "harbour/physics/PhysicsWorld.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace harbour::physics {
namespace {

constexpr double kDt = 0.001;
constexpr double kG = 9.80665;

BoxSettings box_at(const core::Vec3& p, double mass, bool collides = true) {
  BoxSettings b;
  b.mass_kg = mass;
  b.pose.position = p;
  b.collides = collides;
  return b;
}

TEST(PhysicsWorld, FreeFallFollowsTheSemiImplicitEulerRecurrenceAndGravity) {
  PhysicsWorld w({});
  const BodyId b = w.add_box(box_at({0, 0, 100}, 10.0, false));
  const int n = 1000;
  for (int k = 0; k < n; ++k)
    w.step(kDt);
  // dWorldStep: v_n = -g n dt, z_n = z0 - g dt^2 n (n + 1) / 2
  EXPECT_NEAR(w.linear_velocity(b).z, -kG * n * kDt, 1e-9);
  EXPECT_NEAR(w.pose(b).position.z, 100.0 - kG * kDt * kDt * n * (n + 1) / 2.0, 1e-9);
  // and the continuous fall within the integrator's first-order error g dt t / 2
  EXPECT_NEAR(w.pose(b).position.z, 100.0 - 0.5 * kG * 1.0, 0.5 * kG * kDt * 1.0 + 1e-9);
}

TEST(PhysicsWorld, BoxDroppedOnTheGroundComesToRestOnIt) {
  PhysicsWorld w({});
  w.add_ground(0.0);
  const BodyId b = w.add_box(box_at({0, 0, 0.6}, 1000.0));  // 1 m cube, 10 cm above the ground
  int contacts = 0;
  for (int k = 0; k < 3000; ++k) {
    w.step(kDt);
    contacts = std::max(contacts, w.contact_count());
  }
  EXPECT_GT(contacts, 0);
  EXPECT_NEAR(w.pose(b).position.z, 0.5, 0.01);
  EXPECT_LT(std::abs(w.linear_velocity(b).z), 1e-3);
}

TEST(PhysicsWorld, AnImpactIsReportedOnceWithItsClosingSpeed) {
  PhysicsWorld w({});
  w.add_ground(0.0);
  const BodyId b = w.add_box(box_at({0, 0, 0.5 + 1.25}, 1000.0));  // bottom 1.25 m up: lands at sqrt(2 g h)
  std::vector<ImpactEvent> impacts;
  for (int k = 0; k < 2000; ++k) {
    w.step(kDt);
    for (const ImpactEvent& e : w.take_impacts())
      impacts.push_back(e);
  }
  ASSERT_EQ(impacts.size(), 1u);  // resting contact afterwards is not a new impact
  EXPECT_EQ(impacts[0].body, b);
  EXPECT_EQ(impacts[0].other, kWorld);
  EXPECT_NEAR(impacts[0].normal_speed_mps, std::sqrt(2 * kG * 1.25), 0.02);
}

TEST(PhysicsWorld, SliderMotorDrivesTheBodyAtItsSpeed) {
  PhysicsWorld w({});
  const BodyId trolley = w.add_box(box_at({0, 0, 10}, 30000.0, false));
  const auto s = w.add_slider(kWorld, trolley, {1, 0, 0});
  w.set_slider_motor(s, 2.0, 1e6);
  for (int k = 0; k < 2000; ++k)
    w.step(kDt);
  // force-limited run-up: 2 m/s reached after t1 = v m / F = 60 ms, then constant speed: x = v (t - t1 / 2)
  const double t1 = 2.0 * 30000.0 / 1e6;
  EXPECT_NEAR(w.slider_position(s), 2.0 * (2.0 - t1 / 2), 2.0 * kDt);
  EXPECT_NEAR(w.pose(trolley).position.x, w.slider_position(s), 1e-9);  // the body really moved along +x
  EXPECT_NEAR(w.pose(trolley).position.z, 10.0, 1e-5);  // the joint carries its weight (CFM: micrometres)
}

TEST(PhysicsWorld, SliderBetweenTwoBodiesMeasuresTheSecondRelativeToTheFirst) {
  PhysicsWorld w({});
  const BodyId gantry = w.add_box(box_at({0, 0, 10}, 1e6, false));
  const BodyId trolley = w.add_box(box_at({5, 0, 20}, 3e4, false));
  w.add_slider(kWorld, gantry, {0, 1, 0});
  const auto s = w.add_slider(gantry, trolley, {1, 0, 0});
  w.set_slider_motor(s, 1.0, 1e7);
  for (int k = 0; k < 1000; ++k)
    w.step(kDt);
  EXPECT_GT(w.slider_position(s), 0.9);
  EXPECT_NEAR(w.pose(trolley).position.x - w.pose(gantry).position.x - 5.0, w.slider_position(s), 1e-3);
}

// The drive's work: a force-limited run-up of mass m to speed v puts in the kinetic energy m v^2 / 2, on the
// world and between two bodies.
TEST(PhysicsWorld, SliderForceTimesRateIsTheWorkTheMotorDoes) {
  PhysicsWorld w({});
  const BodyId trolley = w.add_box(box_at({0, 0, 10}, 30000.0, false));
  const auto s = w.add_slider(kWorld, trolley, {-2, 0, 0});  // any axis length, either direction
  w.set_slider_motor(s, 2.0, 3e4);                           // 1 m/s^2 for 2 s
  double work = 0.0;
  for (int k = 0; k < 3000; ++k) {
    w.step(kDt);
    work += w.slider_force(s) * w.slider_rate(s) * kDt;
  }
  EXPECT_NEAR(w.slider_force(s), 0.0, 1.0);  // at speed, no force
  EXPECT_NEAR(work, 0.5 * 30000.0 * 2.0 * 2.0, 0.005 * 60000.0);

  // a trolley on a gantry that stands on its rails (a world slider across): the trolley's kinetic energy
  PhysicsWorld two({});
  const BodyId gantry = two.add_box(box_at({0, 0, 10}, 1e6, false));
  const BodyId car = two.add_box(box_at({5, 0, 20}, 3e4, false));
  two.add_slider(kWorld, gantry, {0, 1, 0});
  const auto rail = two.add_slider(gantry, car, {1, 0, 0});
  two.set_slider_motor(rail, -1.5, 3e4);  // towards -x this time
  double trolley_work = 0.0;
  for (int k = 0; k < 3000; ++k) {
    two.step(kDt);
    trolley_work += two.slider_force(rail) * two.slider_rate(rail) * kDt;
  }
  EXPECT_NEAR(two.slider_rate(rail), -1.5, 1e-3);
  EXPECT_NEAR(trolley_work, 0.5 * 3e4 * 1.5 * 1.5, 0.005 * 0.5 * 3e4 * 1.5 * 1.5);
}

// A compound pendulum on a hinge: a 2 m bar hung from its top end swings with the small-angle period
// 2 pi sqrt(I_pivot / (m g d)), I_pivot = m (w^2 + l^2) / 12 + m d^2, d = l / 2.
TEST(PhysicsWorld, AHingedBarSwingsWithTheCompoundPendulumsPeriod) {
  PhysicsWorld w({});
  const double mass = 10.0, width = 0.2, length = 2.0;
  BoxSettings bar = box_at({0, 0, 10.0 - length / 2}, mass, false);
  bar.half_extents_m = {width / 2, width / 2, length / 2};
  const BodyId b = w.add_box(bar);
  const auto hinge = w.add_hinge(kWorld, b, {0, 0, 10.0}, {0, 1, 0});
  w.set_linear_velocity(b, {0.05 * length / 2, 0, 0});  // a small push: ~0.05 rad/s at the centre
  std::vector<double> crossings;                        // times the angle passes zero going up
  double last = w.hinge_angle(hinge);
  for (int k = 1; k <= 20000; ++k) {
    w.step(kDt);
    const double now = w.hinge_angle(hinge);
    if (last < 0.0 && now >= 0.0) crossings.push_back((k - now / (now - last)) * kDt);
    last = now;
  }
  ASSERT_GE(crossings.size(), 5u);
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double d = length / 2, pivot_inertia = mass * (width * width + length * length) / 12.0 + mass * d * d;
  const double expected = 2.0 * std::numbers::pi * std::sqrt(pivot_inertia / (mass * kG * d));
  EXPECT_NEAR(measured, expected, 0.002 * expected);
  // it stays on its pivot: the bar's top end at the anchor
  EXPECT_NEAR(core::length(w.point_position(b, {0, 0, length / 2}) - core::Vec3{0, 0, 10.0}), 0.0, 1e-4);
}

TEST(PhysicsWorld, ABoxOnAPivotSwingsAboutItAsACompoundPendulumAndKeepsItThroughAKeyframe) {
  // a box hung at a point 1.5 m above its centre (a load on a crane hook), pushed in x: it swings about the
  // pivot in both directions with the compound pendulum's period; a keyframe mid-swing continues bit for bit
  const auto build = [](PhysicsWorld& w) {
    const BodyId hook = w.add_kinematic_body({core::Mat3::identity(), {0, 0, 10.0}});
    BoxSettings load = box_at({0, 0, 8.5}, 2000.0, false);
    load.half_extents_m = {1.0, 0.5, 0.5};
    const BodyId b = w.add_box(load);
    w.attach_pivot(hook, b, {0, 0, 10.0});
    return b;
  };
  PhysicsWorld w({});
  const BodyId b = build(w);
  w.set_linear_velocity(b, {0.1, 0.05, 0});
  std::vector<double> crossings;  // times its centre passes under the pivot going +x
  double last = w.pose(b).position.x;
  core::StateWriter saved;
  for (int k = 1; k <= 20000; ++k) {
    if (k == 5000) w.save_state(saved);
    w.step(kDt);
    const double now = w.pose(b).position.x;
    if (last < 0.0 && now >= 0.0) crossings.push_back((k - now / (now - last)) * kDt);
    last = now;
  }
  ASSERT_GE(crossings.size(), 5u);
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double mass = 2000.0, d = 1.5, about_y = mass * (2.0 * 2.0 + 1.0 * 1.0) / 12.0 + mass * d * d;
  const double expected = 2.0 * std::numbers::pi * std::sqrt(about_y / (mass * kG * d));
  EXPECT_NEAR(measured, expected, 0.002 * expected);
  EXPECT_NEAR(core::length(w.point_position(b, {0, 0, d}) - core::Vec3{0, 0, 10.0}), 0.0, 1e-4);
  EXPECT_GT(std::abs(w.pose(b).position.y), 0.0);  // it swings across as well: a pivot, not a hinge

  PhysicsWorld restored({});
  build(restored);
  core::StateReader reader(saved.bytes());
  restored.restore_state(reader);
  for (int k = 5000; k <= 20000; ++k)
    restored.step(kDt);
  EXPECT_EQ(restored.state_hash(), w.state_hash());
}

// A hinge motor spinning up a flywheel puts in its kinetic energy I w^2 / 2 (torque times rate, summed).
TEST(PhysicsWorld, HingeTorqueTimesRateIsTheWorkTheMotorDoes) {
  PhysicsWorld w({});
  BoxSettings disc = box_at({3, 0, 5}, 800.0, false);
  disc.half_extents_m = {1.0, 1.0, 0.25};
  const BodyId b = w.add_box(disc);
  const auto hinge = w.add_hinge(kWorld, b, {3, 0, 5}, {0, 0, 2});  // about its own vertical axis
  w.set_hinge_motor(hinge, 1.5, 400.0);
  double work = 0.0;
  for (int k = 0; k < 4000; ++k) {
    w.step(kDt);
    work += w.hinge_torque(hinge) * w.hinge_rate(hinge) * kDt;
  }
  const double inertia = 800.0 * (2.0 * 2.0 + 2.0 * 2.0) / 12.0;  // about z: m (a^2 + b^2) / 12
  EXPECT_NEAR(w.hinge_rate(hinge), 1.5, 1e-3);
  EXPECT_NEAR(w.hinge_torque(hinge), 0.0, 1.0);  // at speed, no torque
  EXPECT_NEAR(work, 0.5 * inertia * 1.5 * 1.5, 0.005 * 0.5 * inertia * 1.5 * 1.5);
  // the run-up took I w / T_max; the angle is reported in (-pi, pi]
  EXPECT_NEAR(w.hinge_angle(hinge),
              std::remainder(1.5 * (4.0 - 0.5 * inertia * 1.5 / 400.0), 2.0 * std::numbers::pi), 0.01);
}

TEST(PhysicsWorld, SameInputsGiveTheSameStateHash) {
  auto run = [](double push) {
    PhysicsWorld w({});
    w.add_ground(0.0);
    const BodyId a = w.add_box(box_at({0, 0, 2}, 500.0));
    const BodyId b = w.add_box(box_at({0.3, 0.2, 3.5}, 800.0));
    for (int k = 0; k < 2000; ++k) {
      if (k < 100) w.add_force_at(a, w.point_position(a, {0.5, 0, 0}), {push, 0, 0});
      w.step(kDt);
    }
    (void)b;
    return w.state_hash();
  };
  EXPECT_EQ(run(1000.0), run(1000.0));
  EXPECT_NE(run(1000.0), run(1000.0001));
}

TEST(PhysicsWorld, AnImpactCarriesTheMomentumItTookAway) {
  PhysicsWorld w({});
  w.add_ground(0.0, 7);
  const BodyId b = w.add_box(box_at({0, 0, 0.5 + 1.25}, 1000.0));
  std::vector<ImpactEvent> impacts;
  for (int k = 0; k < 1000; ++k) {
    w.step(kDt);
    for (const ImpactEvent& e : w.take_impacts())
      impacts.push_back(e);
  }
  ASSERT_EQ(impacts.size(), 1u);
  EXPECT_EQ(impacts[0].other_surface, 7);
  // the contact stops m v in the impact step, then carries the weight for the rest of the window
  const double v = std::sqrt(2 * kG * 1.25);
  const double expected = 1000.0 * v + 1000.0 * kG * kDt * (PhysicsWorld::kImpulseWindowSteps - 1);
  EXPECT_NEAR(impacts[0].impulse_ns, expected, 0.03 * expected);
  (void)b;
}

TEST(PhysicsWorld, AnOffCentreCentreOfMassTipsTheBoxTowardsIt) {
  auto tilt_after_2s = [](double com_x) {
    PhysicsWorld w({});
    w.add_ground(0.0);
    w.add_static_box({0.1, 1.0, 0.5}, {core::Mat3::identity(), {0, 0, 0.5}});  // a ridge under its middle
    BoxSettings box = box_at({0, 0, 1.25}, 2000.0);
    box.half_extents_m = {2.0, 0.5, 0.25};
    box.center_of_mass_m = {com_x, 0, 0};
    const BodyId b = w.add_box(box);
    EXPECT_NEAR(w.pose(b).position.x, 0.0, 1e-12);  // the pose is the box's centre, not its centre of mass
    for (int k = 0; k < 2000; ++k)
      w.step(kDt);
    // height of the +x end above the -x end
    return w.point_position(b, {2, 0, 0}).z - w.point_position(b, {-2, 0, 0}).z;
  };
  EXPECT_NEAR(tilt_after_2s(0.0), 0.0, 1e-6);
  EXPECT_LT(tilt_after_2s(1.0), -0.5);  // the heavy end went down
  EXPECT_GT(tilt_after_2s(-1.0), 0.5);
}

TEST(PhysicsWorld, AKinematicBodyCarriesWhatRestsOnIt) {
  PhysicsWorld w({});
  const BodyId deck = w.add_kinematic_body({});
  w.add_box_shape(deck, {5, 5, 0.5}, {core::Mat3::identity(), {0, 0, -0.5}}, 1);
  const BodyId box = w.add_box(box_at({0, 0, 0.5}, 1000.0));
  // the deck heaves 0.2 m at 0.1 Hz: the box rides on it
  for (int k = 0; k < 10000; ++k) {
    const double t = k * kDt, omega = 2 * std::numbers::pi * 0.1;
    core::Pose p;
    p.position.z = 0.2 * std::sin(omega * t);
    w.set_kinematic_motion(deck, p, {0, 0, 0.2 * omega * std::cos(omega * t)}, {});
    w.step(kDt);
  }
  EXPECT_NEAR(w.pose(box).position.z - w.pose(deck).position.z, 0.5, 0.003);
}

TEST(PhysicsWorld, ARestoredStateContinuesBitForBit) {
  auto build = [](PhysicsWorld& w) {
    w.add_ground(0.0);
    const BodyId a = w.add_box(box_at({0, 0, 0.6}, 500.0));
    const BodyId b = w.add_box(box_at({0.2, 0.1, 1.7}, 800.0));
    const BodyId c = w.add_box(box_at({3, 0, 0.6}, 300.0));
    return std::array<BodyId, 3>{a, b, c};
  };
  auto push = [](PhysicsWorld& w, std::array<BodyId, 3> bodies, int k) {
    if (k < 300) w.add_force_at(bodies[2], w.point_position(bodies[2], {0.5, 0.2, 0}), {-4000, 0, 0});
    if (k == 400) w.attach(bodies[0], bodies[1]);
  };
  PhysicsWorld original({});
  const auto bodies = build(original);
  core::StateWriter saved;
  for (int k = 0; k < 2500; ++k) {
    if (k == 1200) original.save_state(saved);
    push(original, bodies, k);
    original.step(kDt);
  }
  PhysicsWorld restored({});
  const auto same = build(restored);
  core::StateReader reader(saved.bytes());
  restored.restore_state(reader);
  EXPECT_TRUE(reader.at_end());
  for (int k = 1200; k < 2500; ++k) {
    push(restored, same, k);
    restored.step(kDt);
  }
  EXPECT_EQ(restored.state_hash(), original.state_hash());

  PhysicsWorld other({});
  other.add_ground(0.0);
  other.add_box(box_at({0, 0, 0.6}, 500.0));
  core::StateReader wrong(saved.bytes());
  EXPECT_THROW(other.restore_state(wrong), core::StateError);  // a state of another world is refused
}

}  // namespace
}  // namespace harbour::physics

namespace harbour::physics {
namespace {

// What would drive ODE into its internal asserts (an abort) stops the world instead, saying where.
TEST(PhysicsWorld, ADivergingStateStopsTheWorldBeforeODESeesIt) {
  const core::Vec3 bad_forces[] = {{1e300, 0, 0}, {std::numeric_limits<double>::quiet_NaN(), 0, 0}};
  for (const core::Vec3& force : bad_forces) {
    PhysicsWorld w(WorldSettings{});
    const BodyId b = w.add_box(box_at({0, 0, 10}, 10.0, false));
    w.step(0.001);
    ASSERT_FALSE(w.diverged());
    const std::uint64_t before = w.state_hash();
    w.add_force_at(b, w.pose(b).position, force);
    w.step(0.001);
    EXPECT_TRUE(w.diverged());
    EXPECT_NE(w.divergence().find("body 0: applied force"), std::string::npos) << w.divergence();
    EXPECT_EQ(w.state_hash(), before);  // not stepped
    w.step(0.001);                      // and never again
    EXPECT_EQ(w.state_hash(), before);
  }
  // a finite force that would throw the body faster than anything in a harbour: stopped after the step
  PhysicsWorld w(WorldSettings{});
  const BodyId b = w.add_box(box_at({0, 0, 10}, 10.0, false));
  w.add_force_at(b, w.pose(b).position, {5e8, 0, 0});  // 5e7 m/s^2 for 1 ms: 50 000 m/s
  w.step(0.001);
  EXPECT_TRUE(w.diverged());
  EXPECT_NE(w.divergence().find("body 0: speed"), std::string::npos) << w.divergence();
}

}  // namespace
}  // namespace harbour::physics
