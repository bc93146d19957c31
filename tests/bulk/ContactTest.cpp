#include <gtest/gtest.h>
#include <limits>
#include <memory>

#include <vector>

#include "harbour/bulk/BulkWorld.h"
#include "harbour/core/Units.h"
#include "scenes/BulkScenes.h"

namespace harbour::bulk {
namespace {

constexpr double kDt = 0.001;

// a 1 m x 1 m box bottom with 3 x 3 contact points, dropped on a flat 1 m bed and integrated
// vertically (semi-implicit Euler) under gravity and the penalty force
struct BoxScene {
  explicit BoxScene(double compression_gain, double mass_kg) : mass(mass_kg) {
    Material m = scenes::test_material();
    m.compression_gain = compression_gain;
    world = std::make_unique<BulkWorld>(m, BulkWorldSettings{});
    bed = world->add_grid({60, 60, 0.1}, {});
    for (int j = 0; j < 60; ++j)
      for (int i = 0; i < 60; ++i)
        world->pour(bed, (i + 0.5) * 0.1, (j + 0.5) * 0.1, 0.01);
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        points.push_back({0.5 * a, 0.5 * b, 0.0});
    body.pose.position = {3.0, 3.0, 1.05};
  }

  ContactResult step() {
    body.points = points;
    const ContactResult r = world->contact(body);
    body.linear_velocity.z += (r.force.z / mass - core::kStandardGravity) * kDt;
    body.pose.position.z += body.linear_velocity.z * kDt;
    world->step(kDt, {});
    return r;
  }

  double mass;
  std::unique_ptr<BulkWorld> world;
  int bed = 0;
  std::vector<core::Vec3> points;
  ContactBody body;
};

TEST(Contact, RestingBoxSettlesAtWeightOverStiffness) {
  BoxScene s(4.0, 2000.0);
  ContactResult r;
  for (int n = 0; n < 5000; ++n)
    r = s.step();
  const double k_total = 9 * s.world->settings().contact.stiffness_n_per_m;
  const double expected = s.mass * core::kStandardGravity / k_total;
  EXPECT_EQ(r.points_in_contact, 9);
  EXPECT_NEAR(r.max_penetration_m, expected, 0.05 * expected);
  EXPECT_NEAR(r.force.z, s.mass * core::kStandardGravity, 0.01 * s.mass * core::kStandardGravity);
  EXPECT_NEAR(r.point.x, 3.0, 1e-9);  // symmetric: the resultant acts under the centre
  EXPECT_LT(std::abs(s.body.linear_velocity.z), 1e-4);
}

TEST(Contact, DampingIsHighEnoughThatTheBoxNeverBounces) {
  BoxScene s(4.0, 2000.0);
  bool touched = false;
  for (int n = 0; n < 3000; ++n) {
    const ContactResult r = s.step();
    touched |= r.points_in_contact > 0;
    if (touched) {
      ASSERT_GT(r.points_in_contact, 0) << "box left the surface at step " << n;
    }
  }
}

TEST(Contact, CompressionPushesMaterialAsideAndLeavesADepression) {
  BoxScene s(30.0, 2000.0);
  const double before = s.world->grid(s.bed).total_volume_m3();
  for (int n = 0; n < 4000; ++n)
    s.step();
  const HeightGrid& g = s.world->grid(s.bed);
  EXPECT_LT(g.height(30, 30), 0.98);  // under the box: lower than the 1 m bed
  EXPECT_GT(g.height(36, 30), 1.0);   // just outside the box: a rim of displaced material
  EXPECT_NEAR(g.total_volume_m3(), before, 1e-12 * before);
  EXPECT_LT(s.body.pose.position.z, 1.0);  // and the box has sunk into it
}

TEST(Contact, PointsOffTheGridOrAboveTheSurfaceGiveNoForce) {
  BoxScene s(4.0, 2000.0);
  s.body.pose.position = {3.0, 3.0, 1.2};
  s.body.points = s.points;
  EXPECT_EQ(s.world->contact(s.body).points_in_contact, 0);
  s.body.pose.position = {30.0, 3.0, 0.5};
  EXPECT_EQ(s.world->contact(s.body).force.z, 0.0);
}

TEST(Contact, ANonFiniteBodyIsCountedAsAWarningAndChangesNothing) {
  BoxScene s(4.0, 2000.0);
  const double before = s.world->grid(s.bed).total_volume_m3();
  s.body.pose.position = {3.0, 3.0, std::numeric_limits<double>::quiet_NaN()};
  s.body.points = s.points;
  const ContactResult r = s.world->contact(s.body);
  s.world->step(kDt, {});
  EXPECT_EQ(r.points_in_contact, 0);
  EXPECT_GE(s.world->warnings().count(core::Warning::kNonFinite), 1u);
  EXPECT_EQ(s.world->grid(s.bed).total_volume_m3(), before);
}

}  // namespace
}  // namespace harbour::bulk
