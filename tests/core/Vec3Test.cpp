#include "harbour/core/Vec3.h"

#include <gtest/gtest.h>

#include "harbour/core/Units.h"

namespace harbour::core {
namespace {

TEST(Vec3, CrossProductIsRightHanded) {
  const Vec3 z = cross({1, 0, 0}, {0, 1, 0});
  EXPECT_EQ(z, (Vec3{0, 0, 1}));
}

TEST(Mat3, RotationAboutZTurnsXIntoY) {
  const Vec3 v = Mat3::rotation({0, 0, 1}, deg_to_rad(90.0)) * Vec3{1, 0, 0};
  EXPECT_NEAR(v.x, 0.0, 1e-15);
  EXPECT_NEAR(v.y, 1.0, 1e-15);
}

TEST(Pose, ToLocalInvertsToParent) {
  Pose pose;
  pose.rotation = Mat3::from_roll_pitch_yaw(0.1, -0.2, 0.7);
  pose.position = {3, -4, 5};
  const Vec3 p{1.5, 2.5, -0.5};
  const Vec3 back = pose.to_local(pose.to_parent(p));
  EXPECT_NEAR(back.x, p.x, 1e-12);
  EXPECT_NEAR(back.y, p.y, 1e-12);
  EXPECT_NEAR(back.z, p.z, 1e-12);
}

}  // namespace
}  // namespace harbour::core
