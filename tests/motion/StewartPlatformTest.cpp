#include "harbour/motion/StewartPlatform.h"

#include <gtest/gtest.h>

#include <cmath>

#include "harbour/core/Rng.h"
#include "harbour/io/MotionFiles.h"

namespace harbour::motion {
namespace {

const io::PlatformFile& platform_file() {
  static const io::PlatformFile file = io::load_platform(HARBOUR_DATA_DIR "/motion/platform.yaml");
  return file;
}

TEST(StewartPlatform, PureHeaveLengthsMatchGeometry) {
  const StewartPlatform sp(platform_file().geometry);
  PlatformPose p;
  p[kHeave] = 0.1;
  const ActuatorLengths l = sp.inverse(p);
  const auto& g = sp.geometry();
  for (int i = 0; i < kActuators; ++i) {
    const double dx = g.platform_joints[i].x - g.base_joints[i].x,
                 dy = g.platform_joints[i].y - g.base_joints[i].y;
    EXPECT_NEAR(l[i], std::sqrt(dx * dx + dy * dy + std::pow(g.neutral_height_m + 0.1, 2)), 1e-12);
  }
}

TEST(StewartPlatform, ForwardKinematicsInvertsInverseKinematics) {
  const StewartPlatform sp(platform_file().geometry);
  core::Rng rng(11);
  int tried = 0;
  while (tried < 500) {
    PlatformPose target;
    for (int i = 0; i < 3; ++i)
      target[i] = rng.uniform(-0.15, 0.15);
    for (int i = 3; i < 6; ++i)
      target[i] = rng.uniform(-0.2, 0.2);
    const ActuatorLengths l = sp.inverse(target);
    if (!sp.reachable(l)) continue;
    ++tried;
    PlatformPose solved;  // start from neutral
    ASSERT_TRUE(sp.forward(l, solved));
    for (int i = 0; i < 3; ++i)
      ASSERT_NEAR(solved[i], target[i], 1e-9);
    for (int i = 3; i < 6; ++i)
      ASSERT_NEAR(solved[i], target[i], 1e-9);
  }
}

TEST(StewartPlatform, ScalingKeepsTheCueDirectionAtTheWorkspaceEdge) {
  const StewartPlatform sp(platform_file().geometry);
  PlatformPose big;
  big[kPitch] = 0.5;
  big[kRoll] = 0.4;
  big[kSurge] = 0.2;
  const double s = sp.largest_reachable_scale(big);
  EXPECT_GT(s, 0.1);
  EXPECT_LT(s, 1.0);
  EXPECT_TRUE(sp.reachable(sp.inverse(big * s)));
  EXPECT_FALSE(sp.reachable(sp.inverse(big * (s + 1e-4))));
}

}  // namespace
}  // namespace harbour::motion
