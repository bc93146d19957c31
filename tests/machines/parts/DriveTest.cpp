#include "harbour/machines/parts/Drive.h"

#include <gtest/gtest.h>

#include <cmath>

namespace harbour::sim {
namespace {

constexpr double kDt = 0.001;

DriveSettings trolley() {
  DriveSettings s;
  s.max_speed_mps = 4.0;  // 240 m/min
  s.acceleration_mps2 = 0.5;
  s.deceleration_mps2 = 0.5;
  s.emergency_deceleration_mps2 = 1.2;
  s.min_position_m = -30.0;
  s.max_position_m = 65.0;
  return s;
}

// integrates the axis as an ideal follower of the drive's velocity
struct Axis {
  Drive drive{trolley()};
  double x = 0.0, v = 0.0, worst_acceleration = 0.0;
  DriveOutput step(double lever, bool estop = false) {
    const DriveOutput out = drive.step(lever, x, kDt, estop);
    const double v_new = out.brake ? 0.0 : out.velocity_mps;
    worst_acceleration = std::max(worst_acceleration, std::abs(v_new - v) / kDt);
    v = v_new;
    x += v * kDt;
    return out;
  }
};

TEST(Drive, RampsToFullSpeedAtTheAccelerationLimit) {
  Axis a;
  for (int k = 0; k < 4000; ++k)
    a.step(1.0);
  EXPECT_NEAR(a.v, 2.0, 1e-9);  // halfway after 4 s at 0.5 m/s^2
  Axis b;
  for (int k = 0; k < 8000; ++k)
    b.step(1.0);
  EXPECT_NEAR(b.v, 4.0, 1e-9);
  EXPECT_LE(b.worst_acceleration, 0.5 + 1e-9);
}

TEST(Drive, SlowsDownAheadOfTheLimitSwitchAndStopsOnIt) {
  Axis a;
  for (int k = 0; k < 60000; ++k)
    a.step(1.0);  // hold the lever into the end
  EXPECT_NEAR(a.x, 65.0, 0.01);
  EXPECT_LE(a.x, 65.0 + 1e-9);
  EXPECT_LE(a.worst_acceleration, 0.5 + 1e-6);
  EXPECT_EQ(a.drive.limit_hits(), 1u);
  for (int k = 0; k < 100; ++k)
    a.step(0.0);
  for (int k = 0; k < 100; ++k)
    a.step(1.0);  // push again: a second hit
  EXPECT_EQ(a.drive.limit_hits(), 2u);
}

TEST(Drive, EmergencyStopBrakesAtTheEmergencyDeceleration) {
  Axis a;
  for (int k = 0; k < 10000; ++k)
    a.step(1.0);
  const double x0 = a.x;
  int steps = 0;
  while (a.v > 0.0 && steps < 10000) {
    a.step(1.0, true);
    ++steps;
  }
  EXPECT_NEAR(steps * kDt, 4.0 / 1.2, 0.01);           // v / a
  EXPECT_NEAR(a.x - x0, 4.0 * 4.0 / (2 * 1.2), 0.01);  // v^2 / 2a
  EXPECT_TRUE(a.step(1.0, true).brake);
}

TEST(Drive, BrakeSetsAtRestUnlessFaulty) {
  Drive d(trolley());
  EXPECT_TRUE(d.step(0.0, 0.0, kDt, false).brake);
  EXPECT_FALSE(d.step(0.0, 0.0, kDt, false, true).brake);
}

}  // namespace
}  // namespace harbour::sim
