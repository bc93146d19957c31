#include "harbour/physics/PhysicsWorld.h"

#include <gtest/gtest.h>

#include <cmath>
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
  const int s = w.add_slider(kWorld, trolley, {1, 0, 0});
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
  const int s = w.add_slider(gantry, trolley, {1, 0, 0});
  w.set_slider_motor(s, 1.0, 1e7);
  for (int k = 0; k < 1000; ++k)
    w.step(kDt);
  EXPECT_GT(w.slider_position(s), 0.9);
  EXPECT_NEAR(w.pose(trolley).position.x - w.pose(gantry).position.x - 5.0, w.slider_position(s), 1e-3);
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

}  // namespace
}  // namespace harbour::physics
