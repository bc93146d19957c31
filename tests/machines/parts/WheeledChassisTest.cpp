#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "harbour/machines/parts/WheeledChassis.h"

namespace harbour::sim {
namespace {

constexpr double kDt = 0.001;

// A terminal tractor's chassis (Kalmar Ottawa 4x2 class: wheelbase 2.95 m, published; the rest assumed): 8 t
// with its centre of mass 1.5 m behind the steered front axle, twin tyres on the driven rear axle.
struct Tractor {
  static constexpr double kMass_kg = 8000.0, kFront_m = 1.5, kRear_m = -1.45;
  physics::WorldSettings world_settings;
  physics::PhysicsWorld world{world_settings};
  WheeledChassisSettings settings;
  physics::BodyId body = physics::kWorld;
  std::unique_ptr<WheeledChassis> chassis;

  Tractor() {
    settings.axles = {{kFront_m, 1.0, -0.6, true, false, 1}, {kRear_m, 0.9, -0.6, false, true, 2}};
    settings.tyre.radius_m = 0.55;
    physics::BoxSettings box;
    box.mass_kg = kMass_kg;
    box.half_extents_m = {2.5, 1.25, 0.6};
    box.collides = false;
    box.pose.position = {0, 0, 0.6 + settings.tyre.radius_m - 0.01};
    body = world.add_box(box);
    chassis = std::make_unique<WheeledChassis>(settings, body);
  }
  double forward_mps() const { return dot(world.linear_velocity(body), world.pose(body).rotation.column(0)); }
  // drives `seconds` holding `speed_mps` (a throttle following the speed) at `steer`
  void drive(double seconds, double speed_mps, double steer) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds / kDt)); ++k) {
      const double error = speed_mps - forward_mps();
      chassis->step(
          world, {std::clamp(0.5 * error, 0.0, 1.0), false, std::clamp(-0.5 * error, 0.0, 1.0), steer, false},
          FlatGround());
      world.step(kDt);
    }
  }
  // the turn's radius at the rear axle's centre, from its speed over the yaw rate
  double path_radius_m() const {
    const double yaw_rate = world.angular_velocity(body).z;
    const core::Vec3 rear = world.point_velocity(body, {kRear_m, 0, 0});
    return std::hypot(rear.x, rear.y) / std::abs(yaw_rate);
  }
};

TEST(WheeledChassis, AtWalkingPaceItTurnsOnTheAckermannCircle) {
  // every wheel square to the line to the turn's centre on the rear axle's line: R = L / tan δ
  Tractor t;
  EXPECT_NEAR(t.chassis->reference_x_m(), Tractor::kRear_m, 1e-12);
  const double wheelbase = Tractor::kFront_m - Tractor::kRear_m;
  const double expected = wheelbase / std::tan(t.settings.max_steer_rad);
  // the inner and outer front wheels' angles by Ackermann's geometry
  EXPECT_NEAR(std::tan(t.chassis->wheel_angle_rad(Tractor::kFront_m, 1.0, 1.0)), wheelbase / (expected - 1.0),
              1e-9);
  EXPECT_NEAR(std::tan(t.chassis->wheel_angle_rad(Tractor::kFront_m, -1.0, 1.0)),
              wheelbase / (expected + 1.0), 1e-9);
  t.drive(20.0, 1.5, 1.0);
  EXPECT_GT(t.world.angular_velocity(t.body).z, 0.0);  // + steers left
  EXPECT_NEAR(t.path_radius_m(), expected, 0.05 * expected);
  std::printf("full lock at 1.5 m/s: radius %.3f m against L / tan(delta) = %.3f m\n", t.path_radius_m(),
              expected);
}

TEST(WheeledChassis, FasterItUndersteersByTheBicycleModelsGradient) {
  // steady cornering at 8 m/s: the linear single-track model gives R = (L + K v²) / tan δ with the understeer
  // gradient K = m (b / C_f − a / C_r) / L (a, b: the centre of mass to the front and rear axles; C: an
  // axle's cornering stiffness, twin tyres twice); the kinematic radius L / tan δ is 5 % smaller
  Tractor t;
  const double steer = 0.1 / t.settings.max_steer_rad, v = 8.0;
  t.drive(25.0, v, steer);
  const double wheelbase = Tractor::kFront_m - Tractor::kRear_m, a = Tractor::kFront_m, b = -Tractor::kRear_m;
  const double c_front = 2 * t.settings.tyre.cornering_stiffness_n_per_rad, c_rear = 2 * c_front;
  const double gradient = Tractor::kMass_kg * (b / c_front - a / c_rear) / wheelbase;
  const double speed = t.forward_mps();  // the throttle's proportional hold leaves it a little slow
  const double expected = (wheelbase + gradient * speed * speed) / std::tan(0.1);
  const double kinematic = wheelbase / std::tan(0.1);
  EXPECT_NEAR(speed, v, 0.5);
  EXPECT_NEAR(t.path_radius_m(), expected, 0.015 * expected);
  EXPECT_GT(t.path_radius_m(), kinematic * 1.03);
  std::printf(
      "steady turn at %.2f m/s: radius %.2f m against the bicycle model's %.2f m (kinematic %.2f m)\n", speed,
      t.path_radius_m(), expected, kinematic);
}

// The tractor's chassis with spring brakes on its rear axle of `capacity` times what holds it on an 18 %
// slope (ECE R13's gradient), the slope made by tilting gravity over its flat ground (uphill ahead): how far
// it travels down the slope [m] and how fast it goes [m/s] in `seconds` with only the parking brake set
// (`parking`) or nothing, after standing on its service brakes.
struct SlopeRun {
  double travelled_m = 0.0, speed_mps = 0.0;
};
SlopeRun parked_on_a_slope(double capacity, bool parking, double seconds, double slope_rad) {
  Tractor t;
  const double pull_n = Tractor::kMass_kg * core::kStandardGravity * std::sin(slope_rad);
  t.settings.axles[1].parking_braked = true;
  // four tyres on the rear axle (twins), each giving torque / radius
  t.settings.parking_brake_torque_per_wheel_nm = capacity * pull_n * t.settings.tyre.radius_m / 4.0;
  t.world_settings.gravity = {-core::kStandardGravity * std::sin(slope_rad), 0.0,
                              -core::kStandardGravity * std::cos(slope_rad)};
  physics::PhysicsWorld world(t.world_settings);
  physics::BoxSettings box;
  box.mass_kg = Tractor::kMass_kg;
  box.half_extents_m = {2.5, 1.25, 0.6};
  box.collides = false;
  box.pose.position = {0, 0, 0.6 + t.settings.tyre.radius_m - 0.01};
  const physics::BodyId body = world.add_box(box);
  WheeledChassis chassis(t.settings, body);
  for (int k = 0; k < 3000; ++k) {  // standing on the service brakes
    chassis.step(world, {0.0, false, 1.0, 0.0, false}, FlatGround());
    world.step(kDt);
  }
  const double from = world.pose(body).position.x;
  for (int k = 0; k < static_cast<int>(std::lround(seconds / kDt)); ++k) {
    chassis.step(world, {0.0, false, 0.0, 0.0, parking}, FlatGround());
    world.step(kDt);
  }
  return {from - world.pose(body).position.x, -world.linear_velocity(body).x};
}

TEST(WheeledChassis, TheParkingBrakeHoldsOnASlopeUpToItsCapacityAndRollsAwayBeyondIt) {
  // static friction while the spring brakes hold more than the pull down the slope; beyond, the chassis
  // rolls away from rest at a = g sin a - P / m - crr g cos a (P the spring brakes' force, crr by weight)
  const double slope = std::atan(0.18), seconds = 3.0;
  const SlopeRun held = parked_on_a_slope(1.25, true, 10.0, slope);
  EXPECT_LT(std::abs(held.travelled_m), 1e-3);
  const TyreSettings tyre;
  const double g = core::kStandardGravity;
  for (const auto& [capacity, parking] : {std::pair{0.5, true}, std::pair{0.5, false}}) {
    const SlopeRun run = parked_on_a_slope(capacity, parking, seconds, slope);
    const double braking = parking ? capacity * g * std::sin(slope) : 0.0;
    const double expected = g * std::sin(slope) - braking - tyre.rolling_resistance * g * std::cos(slope);
    const double measured = 2.0 * run.travelled_m / (seconds * seconds);
    EXPECT_NEAR(measured, expected, 0.05 * expected) << (parking ? "half the pull" : "released");
    EXPECT_NEAR(run.speed_mps, expected * seconds, 0.05 * expected * seconds);
    std::printf("18 %% slope, parking brake %s: %.3f m/s^2 from rest against %.3f\n",
                parking ? "at half the pull" : "released", measured, expected);
  }
  std::printf("18 %% slope, parking brake at 1.25 times the pull: moved %.5f m in 10 s\n", held.travelled_m);
}

TEST(WheeledChassis, TheGearboxPicksTheGearWithTheMostTorqueWithinTheEngineSpeed) {
  const DrivetrainSettings d;
  const double r = 0.55;
  // standing: first gear at the curve's first point
  const auto [standing, first] = drivetrain_wheel_torque_nm(d, r, 1.0, 0.0);
  EXPECT_EQ(first, 1);
  EXPECT_NEAR(standing, 500.0 * 5.0 * 6.0 * 0.85, 1e-9);
  // at 10 m/s first and second gear would over-speed the engine (2200 rpm): 10/0.55 rad/s * 30 * 60 / 2π
  // = 5209 rpm in first
  const auto [fast, gear] = drivetrain_wheel_torque_nm(d, r, 1.0, 10.0);
  EXPECT_GE(gear, 3);
  EXPECT_GT(fast, 0.0);
  EXPECT_EQ(drivetrain_wheel_torque_nm(d, r, 1.0, 40.0).first, 0.0);  // beyond top gear's governor
  EXPECT_NEAR(drivetrain_wheel_torque_nm(d, r, 0.5, 0.0).first, 0.5 * standing, 1e-9);

  // a torque converter multiplies the held engine's torque: by its stall ratio standing, by 1 at the curve's
  // first engine speed (800 rpm in first: 800 / 30 / 60 * 2π * 0.55 m = 1.536 m/s)
  DrivetrainSettings converter = d;
  converter.converter_stall_ratio = 2.2;
  EXPECT_NEAR(drivetrain_wheel_torque_nm(converter, r, 1.0, 0.0).first, 2.2 * standing, 1e-9);
  const double coupling_mps = 800.0 / (5.0 * 6.0) / 60.0 * 2.0 * std::numbers::pi * r;
  EXPECT_NEAR(drivetrain_wheel_torque_nm(converter, r, 1.0, 0.5 * coupling_mps).first, 1.6 * standing, 1e-6);
  EXPECT_NEAR(drivetrain_wheel_torque_nm(converter, r, 1.0, coupling_mps * 1.0001).first,
              drivetrain_wheel_torque_nm(d, r, 1.0, coupling_mps * 1.0001).first, 1e-9);
}

}  // namespace
}  // namespace harbour::sim
