#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "harbour/machines/parts/Tyre.h"

namespace harbour::sim {
namespace {

constexpr double kG = 9.80665;
constexpr double kDt = 0.001;

// A 12 t rigid chassis (a box, not colliding) on four tyres at (±2, ±1) m, hubs 0.8 m below its centre, on a
// flat quay at z = 0; the tyres are the only thing holding it up.
struct Cart {
  physics::WorldSettings settings;
  physics::PhysicsWorld world{settings};
  physics::BodyId body = physics::kWorld;
  TyreSettings tyre;
  std::array<core::Vec3, 4> hubs{{{2, 1, -0.8}, {2, -1, -0.8}, {-2, 1, -0.8}, {-2, -1, -0.8}}};
  static constexpr double kMass_kg = 12000.0;

  explicit Cart(double speed_mps) {
    physics::BoxSettings box;
    box.mass_kg = kMass_kg;
    box.half_extents_m = {2.5, 1.2, 0.5};
    box.collides = false;
    // standing on the tyres' static sag
    box.pose.position = {0, 0, tyre.radius_m + 0.8 - kMass_kg * kG / (4 * tyre.vertical_stiffness_n_per_m)};
    body = world.add_box(box);
    world.set_linear_velocity(body, {speed_mps, 0, 0});
  }
  // one step; returns the tyres' summed normal force
  double step(const TyreCommand& command) {
    double normal = 0.0;
    for (const core::Vec3& hub : hubs)
      normal += apply_tyre(world, body, hub, tyre, command, FlatGround()).normal_n;
    world.step(kDt);
    return normal;
  }
};

TEST(Tyre, FourTyresCarryTheChassisWeightOnTheirSpringsSag) {
  Cart cart(0.0);
  double normal = 0.0;
  for (int k = 0; k < 3000; ++k)
    normal = cart.step({});
  EXPECT_NEAR(normal, Cart::kMass_kg * kG, 0.001 * Cart::kMass_kg * kG);
  const double sag = Cart::kMass_kg * kG / (4 * cart.tyre.vertical_stiffness_n_per_m);
  EXPECT_NEAR(cart.world.pose(cart.body).position.z, cart.tyre.radius_m + 0.8 - sag, 1e-4);
  EXPECT_LT(std::abs(cart.world.linear_velocity(cart.body).x), 1e-3);  // held, not creeping
}

TEST(Tyre, LockedBrakesStopInTheSlidingDistance) {
  // locked wheels slide at µ·Fz: the chassis stops in v² / (2 µ g)
  const double v = 8.0;
  Cart cart(v);
  const double start = cart.world.pose(cart.body).position.x;
  for (int k = 0; k < 20000 && cart.world.linear_velocity(cart.body).x > 0.01; ++k)
    cart.step({0.0, 0.0, 1e6});
  const double distance = cart.world.pose(cart.body).position.x - start;
  const double expected = v * v / (2 * cart.tyre.friction * kG);
  EXPECT_NEAR(distance, expected, 0.05 * expected);
  std::printf("braking from %.0f m/s: %.3f m against v^2/(2 mu g) = %.3f m\n", v, distance, expected);
}

TEST(Tyre, RollingFreelyTheChassisSlowsByTheRollingResistance) {
  // no drive, no brake: the deceleration is C_rr g
  Cart cart(5.0);
  for (int k = 0; k < 10000; ++k)
    cart.step({});
  const double expected = 5.0 - cart.tyre.rolling_resistance * kG * 10.0;
  EXPECT_NEAR(cart.world.linear_velocity(cart.body).x, expected, 0.02 * (5.0 - expected));
}

TEST(Tyre, ADriveTorqueAcceleratesByTorqueOverRadiusUntilTheTyresSpin) {
  // below the friction limit a = (4 T / r − C_rr m g) / m; above it the tyres spin and it is µ g
  Cart low(0.0), high(0.0);
  for (int k = 0; k < 5000; ++k) {
    low.step({0.0, 2000.0, 0.0});
    high.step({0.0, 40000.0, 0.0});
  }
  const double a_low =
      (4 * 2000.0 / low.tyre.radius_m - low.tyre.rolling_resistance * Cart::kMass_kg * kG) / Cart::kMass_kg;
  EXPECT_NEAR(low.world.linear_velocity(low.body).x / 5.0, a_low, 0.02 * a_low);
  EXPECT_NEAR(high.world.linear_velocity(high.body).x / 5.0, high.tyre.friction * kG,
              0.02 * high.tyre.friction * kG);
}

TEST(Tyre, ASideslipIsResistedByTheCorneringStiffnessUpToTheFrictionCircle) {
  // at small slip angles F_y = −Cα α; a large one saturates at µ Fz; a locked wheel sliding keeps no more
  // than µ Fz in all (the friction circle)
  TyreSettings t;
  const double fz = 30000.0, sag = fz / t.vertical_stiffness_n_per_m;
  const TyreForces small = tyre_forces(t, {}, sag, 0.0, 10.0, 0.1);
  EXPECT_NEAR(small.lateral_n, -t.cornering_stiffness_n_per_rad * std::atan(0.01), 1e-6);
  EXPECT_FALSE(small.sliding);
  const TyreForces skid = tyre_forces(t, {}, sag, 0.0, 10.0, 5.0);
  EXPECT_NEAR(std::hypot(skid.lateral_n, skid.longitudinal_n), t.friction * fz, 1e-6);
  EXPECT_TRUE(skid.sliding);
  const TyreForces locked = tyre_forces(t, {0.0, 0.0, 1e6}, sag, 0.0, 10.0, 1.0);
  EXPECT_NEAR(std::hypot(locked.lateral_n, locked.longitudinal_n), t.friction * fz, 1e-6);
  EXPECT_LT(locked.longitudinal_n, 0.0);
  EXPECT_EQ(tyre_forces(t, {}, -0.01, 0.0, 10.0, 1.0).normal_n, 0.0);  // off the ground
}

}  // namespace
}  // namespace harbour::sim
