// The path follower of the vehicles' scripted operators (sim/PurePursuit), against plane geometry.
#include "harbour/machines/parts/PurePursuit.h"

#include <gtest/gtest.h>

#include <vector>

namespace harbour::sim {
namespace {

void expect_point(const core::Vec3& got, double x, double y) {
  EXPECT_NEAR(got.x, x, 1e-12);
  EXPECT_NEAR(got.y, y, 1e-12);
  EXPECT_EQ(got.z, 0.0) << "a ground-plane point";
}

TEST(PurePursuit, ThePointAheadIsTheLookaheadAlongThePathFromTheNearestPoint) {
  // an L: 20 m east, then 10 m north
  const std::vector<core::Vec3> path = {{0, 0, 0}, {20, 0, 0}, {20, 10, 0}};
  expect_point(point_ahead(path, {5, 3, 1.5}, 4.0), 9, 0);   // nearest (5, 0); height ignored
  expect_point(point_ahead(path, {18, -2, 0}, 5.0), 20, 3);  // round the corner: 2 m east, 3 m north
  expect_point(point_ahead(path, {-4, 1, 0}, 2.0), 2, 0);    // before the start: from the first point
  expect_point(point_ahead(path, {20, 8, 0}, 6.0), 20, 10);  // past the end: its last point
  expect_point(point_ahead(path, {21, 4, 0}, 0.0), 20, 4);   // no lookahead: the nearest point
  // nearest to the second leg although the first is as near by x: the distance decides
  expect_point(point_ahead(path, {19, 7, 0}, 1.0), 20, 8);
}

TEST(PurePursuit, TheDistanceAlongThePathIsTheNearestPointsArcLength) {
  // the same L: 20 m east, then 10 m north (30 m in all)
  const std::vector<core::Vec3> path = {{0, 0, 0}, {20, 0, 0}, {20, 10, 0}};
  EXPECT_NEAR(distance_along(path, {5, 3, 7.0}), 5.0, 1e-12);   // on the first leg; height ignored
  EXPECT_NEAR(distance_along(path, {21, 4, 0}), 24.0, 1e-12);   // on the second: 20 m and 4 m more
  EXPECT_NEAR(distance_along(path, {-4, 1, 0}), 0.0, 1e-12);    // before the start
  EXPECT_NEAR(distance_along(path, {20, 15, 0}), 30.0, 1e-12);  // past the end
  EXPECT_NEAR(distance_along(path, {19, 7, 0}), 27.0, 1e-12);   // the nearer leg decides
}

}  // namespace
}  // namespace harbour::sim
