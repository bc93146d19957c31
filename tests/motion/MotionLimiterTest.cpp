// The platform's motion limiter on its own, against the kinematics of a bang-bang move.
#include "harbour/motion/MotionLimiter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace harbour::motion {
namespace {

constexpr double kDt = 0.001;

MotionLimits limits(double v, double a) {
  MotionLimits l;
  for (int i = 0; i < kDofCount; ++i) {
    l.max_velocity[i] = v;
    l.max_acceleration[i] = a;
  }
  return l;
}

// A step of 0.1 m in surge with 0.5 m/s and 2 m/s^2 allowed: the fastest move is a triangle (peak sqrt(a d) =
// 0.447 m/s, under the speed limit) lasting 2 sqrt(d / a) = 0.447 s; the limiter takes that long within a few
// steps, never exceeds either limit, never overshoots, and stops on the target.
TEST(MotionLimiter, AStepIsTheBangBangMoveWithinItsLimits) {
  MotionLimiter limiter(limits(0.5, 2.0));
  PlatformPose target;
  target[kSurge] = 0.1;
  double peak = 0.0, worst_acceleration = 0.0, furthest = 0.0, previous_v = 0.0;
  int steps = 0;
  for (; steps < 5000; ++steps) {
    limiter.step(target, kDt);
    const double v = limiter.velocity()[kSurge];
    peak = std::max(peak, std::abs(v));
    worst_acceleration = std::max(worst_acceleration, std::abs(v - previous_v) / kDt);
    furthest = std::max(furthest, limiter.pose()[kSurge]);
    previous_v = v;
    if (std::abs(limiter.pose()[kSurge] - 0.1) < 1e-9 && std::abs(v) < 1e-9) break;
  }
  const double ideal_s = 2.0 * std::sqrt(0.1 / 2.0);
  EXPECT_NEAR(steps * kDt, ideal_s, 0.01) << "the move's time";
  EXPECT_NEAR(peak, std::sqrt(2.0 * 0.1), 0.01) << "the triangle's peak speed";
  EXPECT_LE(worst_acceleration, 2.0 + 1e-9);
  EXPECT_LE(furthest, 0.1 + 1e-6) << "no overshoot (past a micrometre)";
  std::printf("furthest %.9f m, %d steps\n", furthest, steps);
  for (int i = 0; i < kDofCount; ++i) {
    if (i != kSurge) {
      EXPECT_EQ(limiter.pose()[i], 0.0);
    }
  }
}

// A long move reaches the speed limit and cruises: d = 1 m, v = 0.5, a = 2 takes d / v + v / a = 2.25 s.
TEST(MotionLimiter, ALongMoveCruisesAtTheSpeedLimit) {
  MotionLimiter limiter(limits(0.5, 2.0));
  PlatformPose target;
  target[kHeave] = -1.0;
  double peak = 0.0;
  int steps = 0;
  for (; steps < 10000; ++steps) {
    limiter.step(target, kDt);
    peak = std::max(peak, std::abs(limiter.velocity()[kHeave]));
    if (std::abs(limiter.pose()[kHeave] + 1.0) < 1e-9 && std::abs(limiter.velocity()[kHeave]) < 1e-9) break;
  }
  EXPECT_NEAR(steps * kDt, 1.0 / 0.5 + 0.5 / 2.0, 0.01);
  EXPECT_NEAR(peak, 0.5, 1e-9);
}

// Two axes at once are scaled as one vector: the pose moves along the straight line to the target, so a cue
// keeps its direction however the limits cut it.
TEST(MotionLimiter, TwoAxesMoveTogetherAlongTheLineToTheTarget) {
  MotionLimiter limiter(limits(0.5, 2.0));
  PlatformPose target;
  target[kSurge] = 0.3;
  target[kSway] = -0.1;
  double worst_off_line = 0.0;
  for (int n = 0; n < 3000; ++n) {
    limiter.step(target, kDt);
    worst_off_line = std::max(worst_off_line, std::abs(limiter.pose()[kSway] + limiter.pose()[kSurge] / 3.0));
  }
  EXPECT_LT(worst_off_line, 1e-12);
  EXPECT_NEAR(limiter.pose()[kSurge], 0.3, 1e-9);
  EXPECT_NEAR(limiter.pose()[kSway], -0.1, 1e-9);
}

}  // namespace
}  // namespace harbour::motion
