#include "harbour/motion/MotionSystem.h"

#include <gtest/gtest.h>

#include <cmath>

#include "harbour/core/Rng.h"
#include "harbour/core/Units.h"
#include "harbour/io/MotionFiles.h"

namespace harbour::motion {
namespace {

MotionSettings settings(const std::string& machine) {
  const auto platform = io::load_platform(HARBOUR_DATA_DIR "/motion/platform.yaml");
  MotionSettings s;
  s.washout = io::load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml",
                               std::string(HARBOUR_DATA_DIR "/machines/") + machine + ".yaml");
  s.geometry = platform.geometry;
  s.limits = platform.limits;
  return s;
}

// ten minutes of violent random driving: specific force and rates as a random walk, impacts, rough ground
TEST(MotionSystem, ActuatorsStayInTheirStrokeAndAxesWithinLimitsUnderLongRandomMotion) {
  const MotionSettings s = settings("tractor");
  MotionSystem system(s, 5);
  core::Rng rng(99);
  MotionCue cue;
  ShortCueInputs inputs;
  PlatformPose previous, previous_velocity;
  const double dt = system.step_s();
  double min_scale = 1.0;
  long interventions = 0;
  for (int k = 0; k < 60000; ++k) {
    cue.specific_force_mps2.x = std::clamp(cue.specific_force_mps2.x + rng.uniform(-0.5, 0.5), -8.0, 8.0);
    cue.specific_force_mps2.y = std::clamp(cue.specific_force_mps2.y + rng.uniform(-0.5, 0.5), -8.0, 8.0);
    cue.specific_force_mps2.z = std::clamp(cue.specific_force_mps2.z + rng.uniform(-0.5, 0.5), 0.0, 20.0);
    cue.angular_velocity_rad_s.z =
        std::clamp(cue.angular_velocity_rad_s.z + rng.uniform(-0.1, 0.1), -1.0, 1.0);
    inputs.ground_speed_mps = 8.0;
    inputs.engine_load = 1.0;
    inputs.impact_speed_mps = rng.below(500) == 0 ? 1.5 : 0.0;
    const PlatformFrame f = system.step(cue, inputs);
    min_scale = std::min(min_scale, f.cue_scale);
    for (int i = 0; i < kActuators; ++i) {
      ASSERT_GE(f.lengths[i], s.geometry.min_length_m) << "step " << k;
      ASSERT_LE(f.lengths[i], s.geometry.max_length_m) << "step " << k;
    }
    // the axis limits hold on every step the workspace safety net did not have to act
    const bool intervened = system.workspace_interventions() != interventions;
    interventions = system.workspace_interventions();
    for (int i = 0; i < kDofCount; ++i) {
      const double v = (f.pose[i] - previous[i]) / dt;
      if (!intervened) {
        ASSERT_LE(std::abs(v), s.limits.max_velocity[i] * (1 + 1e-9)) << "axis " << i << " step " << k;
        ASSERT_LE(std::abs(v - previous_velocity[i]), s.limits.max_acceleration[i] * dt * (1 + 1e-6) + 1e-12)
            << "axis " << i << " step " << k;
      }
      previous_velocity[i] = v;
    }
    previous = f.pose;
  }
  EXPECT_LT(min_scale, 0.5);    // the workspace limit was actually reached, often
  EXPECT_LE(interventions, 6);  // and the safety net stayed rare (at most 1 in 10^4 steps)
}

// One axis a hair from its target (its braking speed once cancelled to zero and stopped every axis: the
// platform froze in an STS exercise) must not hold the others back.
TEST(MotionSystem, AnAxisAHairFromItsTargetDoesNotFreezeTheOthers) {
  MotionLimiter limiter(settings("sts").limits);
  PlatformPose target;
  target[kHeave] = -1e-19;
  limiter.reset(target);
  target[kSurge] = 0.05;
  target[kHeave] = -2e-19;
  for (int k = 0; k < 100; ++k)
    limiter.step(target, 0.01);
  EXPECT_NEAR(limiter.pose()[kSurge], 0.05, 1e-6);
  EXPECT_NEAR(limiter.pose()[kHeave], -2e-19, 1e-20);
}

TEST(MotionSystem, VehiclesAreCuedHarderThanGantryCranes) {
  // the same braking gives a much larger surge onset on a terminal tractor than on an STS crane
  const MotionSettings sts = settings("sts"), tractor = settings("tractor");
  ClassicalWashout a(sts.washout), b(tractor.washout);
  MotionCue brake;
  brake.specific_force_mps2 = {-2.0, 0, core::kStandardGravity};
  double sts_peak = 0, tractor_peak = 0;
  for (int k = 0; k < 100; ++k) {
    sts_peak = std::max(sts_peak, std::abs(a.step(brake)[kSurge]));
    tractor_peak = std::max(tractor_peak, std::abs(b.step(brake)[kSurge]));
  }
  EXPECT_GT(tractor.washout.surge_sway.gain, 2 * sts.washout.surge_sway.gain);
  EXPECT_GT(tractor_peak, 2 * sts_peak);
}

TEST(MotionSystem, AnImpactRingsInHeaveAndDiesAway) {
  MotionSystem system(settings("sts"));
  ShortCueInputs hit;
  hit.impact_speed_mps = 1.0;
  double peak = 0.0;
  PlatformFrame f = system.step({}, hit);
  for (int k = 0; k < 50; ++k)
    peak = std::max(peak, std::abs((f = system.step({})).pose[kHeave]));
  EXPECT_GT(peak, 0.002);
  for (int k = 0; k < 300; ++k)
    f = system.step({});
  EXPECT_LT(std::abs(f.pose[kHeave]), 1e-4);
}

}  // namespace
}  // namespace harbour::motion
