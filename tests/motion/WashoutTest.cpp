#include "harbour/motion/Washout.h"

#include <gtest/gtest.h>

#include <cmath>

#include "harbour/core/Units.h"

namespace harbour::motion {
namespace {

constexpr double kG = core::kStandardGravity;

MotionCue surge(double a) {
  MotionCue c;
  c.specific_force_mps2 = {a, 0, kG};
  return c;
}

TEST(Washout, AtRestThePlatformStaysAtNeutral) {
  ClassicalWashout w({});
  PlatformPose p;
  for (int k = 0; k < 1000; ++k)
    p = w.step({});
  for (int i = 0; i < kDofCount; ++i)
    EXPECT_NEAR(p[i], 0.0, 1e-12);
}

TEST(Washout, SustainedAccelerationIsWashedOutAndRenderedByTilt) {
  const WashoutSettings s;
  ClassicalWashout w(s);
  const double step_s = 1.0 / s.rate_hz;
  double previous_pitch = 0.0, fastest_tilt = 0.0, peak_surge = 0.0;
  PlatformPose p;
  for (int k = 0; k < 6000; ++k) {  // 60 s of 1 m/s^2 forward
    p = w.step(surge(1.0));
    fastest_tilt = std::max(fastest_tilt, std::abs(p[kPitch] - previous_pitch) / step_s);
    previous_pitch = p[kPitch];
    peak_surge = std::max(peak_surge, p[kSurge]);
  }
  EXPECT_GT(peak_surge, 0.05);        // the onset moved the platform forward
  EXPECT_NEAR(p[kSurge], 0.0, 1e-3);  // and it came back
  // nose up (negative pitch) so gravity supplies gain * 1 m/s^2 along the seat back
  EXPECT_NEAR(p[kPitch], -std::asin(s.tilt.gain * 1.0 / kG), 1e-4);
  EXPECT_LE(fastest_tilt, s.tilt.max_rate_rad_s + 1e-12);
}

TEST(Washout, TiltNeverExceedsItsLimit) {
  const WashoutSettings s;
  ClassicalWashout w(s);
  PlatformPose p;
  for (int k = 0; k < 6000; ++k)
    p = w.step(surge(-9.0));  // hard braking
  EXPECT_NEAR(p[kPitch], s.tilt.max_angle_rad, 1e-9);
}

// The false reversed cue: a 2 s, 1 m/s^2 acceleration pulse. Classical washout alone (the bare filter) brakes
// the platform against the cue before the pulse even ends; the false-cue limit bounds every acceleration that
// opposes the demanded cue (or comes with none demanded) to false_cue_limit_mps2, and never swings the
// platform through neutral.
TEST(Washout, FalseCuesAreBoundedByTheLimit) {
  const WashoutSettings s;
  ClassicalWashout w(s);
  TustinFilter bare(ClassicalWashout::translation_to_displacement(s.surge_sway), 0.01);
  const double dt = 1.0 / s.rate_hz;
  double x_prev2 = 0, x_prev = 0, b_prev2 = 0, b_prev = 0, onset = 0, worst_false = 0, bare_reversed = 0,
         lowest = 0;
  double x = 0;
  for (int k = 0; k < 6000; ++k) {
    const double input = k < 200 ? 1.0 : 0.0;
    x = w.step(surge(input))[kSurge];
    const double b = bare.step(s.surge_sway.gain * input);
    const double a = (x - 2 * x_prev + x_prev2) / (dt * dt), ab = (b - 2 * b_prev + b_prev2) / (dt * dt);
    if (k > 1) {
      if (input > 0 && a > 0) onset = std::max(onset, a);
      if (!(input > 0 && a > 0))
        worst_false = std::max(worst_false, std::abs(a));  // against or without a cue
      bare_reversed = std::min(bare_reversed, ab);
    }
    lowest = std::min(lowest, x);
    x_prev2 = x_prev, x_prev = x, b_prev2 = b_prev, b_prev = b;
  }
  EXPECT_GT(onset, 0.4);                   // the onset cue is intact
  EXPECT_GT(-bare_reversed, 0.5 * onset);  // the bare filter's reversal is large
  EXPECT_LE(worst_false, s.surge_sway.false_cue_limit_mps2 * (1 + 1e-6));  // ours is bounded
  EXPECT_GE(lowest, -1e-6);                                                // no swing through neutral
  EXPECT_NEAR(x, 0.0, 1e-3);                                               // and it still washes out
}

TEST(Washout, RotationOnsetFollowsTheRateThenReturns) {
  const WashoutSettings s;
  ClassicalWashout w(s);
  MotionCue c;
  c.angular_velocity_rad_s = {0, 0, 0.2};  // slewing at 0.2 rad/s
  const PlatformPose first = w.step(c);
  // the onset follows the (scaled) rate: after one step about gain * rate * T / 2 (trapezoid from rest)
  EXPECT_NEAR(first[kYaw], s.rotation.gain * 0.2 * 0.01 / 2, 0.05 * s.rotation.gain * 0.2 * 0.01 / 2);
  PlatformPose p;
  for (int k = 0; k < 1000; ++k)
    p = w.step(c);
  EXPECT_NEAR(p[kYaw], 0.0, 1e-6);
}

}  // namespace
}  // namespace harbour::motion
