#include <gtest/gtest.h>

#include "harbour/bulk/BulkWorld.h"
#include "scenes/BulkScenes.h"

namespace harbour::bulk {
namespace {

constexpr double kDt = 0.001;

// a flat 2 m deep bed of material under a grab resting on it
struct BedScene {
  GrabSettings settings{.width_m = 2.0,
                        .max_opening_m = 3.0,
                        .max_depth_m = 1.0,
                        .sinking_speed_mps = 0.25,
                        .spill_speed_mps = 1.5,
                        .capacity_m3 = 20.0,
                        .closing_time_s = 6.0};
  BulkWorld world{scenes::test_material(), BulkWorldSettings{.spill_level_m = -50.0}};
  int bed = world.add_grid({100, 100, 0.1}, {});
  int grab = world.add_grab(settings);

  BedScene() {
    for (int j = 0; j < 100; ++j)
      for (int i = 0; i < 100; ++i)
        world.pour(bed, (i + 0.5) * 0.1, (j + 0.5) * 0.1, 2.0 * 0.01);
  }
};

TEST(Grab, LoadsOpeningTimesWidthTimesSinkingSpeedPerStep) {
  BedScene s;
  GrabCommand c = scenes::grab_at({5.0, 5.0, 2.0}, 1.0);
  double last = 0.0;
  for (int n = 0; n < 1000; ++n) {
    const double w = s.world.grab(s.grab).opening_m;  // opening during this step
    s.world.step(kDt, {&c, 1});
    c.pose.position.z -= s.settings.sinking_speed_mps * kDt;  // the grab sinks as it cuts
    const double loaded = s.world.grab(s.grab).load_m3 - last;
    last = s.world.grab(s.grab).load_m3;
    ASSERT_TRUE(s.world.grab(s.grab).digging);
    // the footprint is counted in whole 10 cm cells: within one cell row of w x W
    const double expected = w * s.settings.width_m * s.settings.sinking_speed_mps * kDt;
    ASSERT_NEAR(loaded, expected, 0.1 * s.settings.width_m * 2 * s.settings.sinking_speed_mps * kDt)
        << "step " << n;
  }
}

TEST(Grab, StopsAtItsDepthAndNeverCreatesMass) {
  BedScene s;
  GrabCommand c = scenes::grab_at({5.0, 5.0, 2.0}, 1.0);
  const double before = s.world.grid(s.bed).total_volume_m3();
  for (int n = 0; n < 6000; ++n) {
    s.world.step(kDt, {&c, 1});
    if (s.world.grab(s.grab).digging) c.pose.position.z -= s.settings.sinking_speed_mps * kDt;
  }
  const GrabState& g = s.world.grab(s.grab);
  EXPECT_LE(g.cut_depth_m, s.settings.max_depth_m + s.settings.sinking_speed_mps * kDt);
  EXPECT_GE(g.cut_depth_m, s.settings.max_depth_m);
  EXPECT_LE(g.load_m3, s.settings.capacity_m3);
  EXPECT_NEAR(before - s.world.grid(s.bed).total_volume_m3(), g.load_m3, 1e-9);
}

TEST(Grab, NeverTakesMoreThanItsCapacity) {
  BedScene s;
  s.settings.capacity_m3 = 1.0;
  BulkWorld world{scenes::test_material(), {}};
  const int bed = world.add_grid({100, 100, 0.1}, {});
  const int grab = world.add_grab(s.settings);
  world.add_heap(bed, 5.0, 5.0, 5.0);
  GrabCommand c = scenes::grab_at({5.0, 5.0, 0.0}, 1.0);
  for (int n = 0; n < 6000; ++n)
    world.step(kDt, {&c, 1});
  EXPECT_NEAR(world.grab(grab).load_m3, 1.0, 1e-12);
}

TEST(Grab, SpillsThroughItsOpeningAtTheSpillSpeed) {
  BedScene s;
  GrabCommand c = scenes::grab_at({5.0, 5.0, 2.0}, 1.0);
  for (int n = 0; n < 6000; ++n) {
    s.world.step(kDt, {&c, 1});
    if (s.world.grab(s.grab).digging) c.pose.position.z -= s.settings.sinking_speed_mps * kDt;
  }
  c.pose.position.z = 10.0;
  c.close_rate = -1.0;
  double last = s.world.grab(s.grab).load_m3;
  for (int n = 0; n < 200; ++n) {
    s.world.step(kDt, {&c, 1});
    const GrabState& g = s.world.grab(s.grab);
    const double out = last - g.load_m3;
    last = g.load_m3;
    ASSERT_NEAR(out, g.opening_m * s.settings.width_m * s.settings.spill_speed_mps * kDt, 1e-12);
  }
}

TEST(Grab, AGrabShuttingBeyondItsTipsReachLoadsNothing) {
  BedScene s;
  // the tips swing down d = 1 m on their arc as the jaws shut: from 1.5 m above the bed they never reach it
  GrabCommand c = scenes::grab_at({5.0, 5.0, 3.5}, 1.0);
  for (int n = 0; n < 6000; ++n)
    s.world.step(kDt, {&c, 1});
  EXPECT_EQ(s.world.grab(s.grab).load_m3, 0.0);
}

TEST(Grab, TheJawTipsSwingDownTheirArcIntoTheMaterial) {
  // held 0.5 m above the bed, the tips (d (1 - w / w_max) below the jaws) reach it half shut and cut down
  // with their arc: the bite is the triangle under it, depth 0.5 m at the middle, 1.5 m wide: W d w_max / 8
  BedScene s;
  GrabCommand c = scenes::grab_at({5.0, 5.0, 2.5}, 1.0);
  for (int n = 0; n < 6000; ++n) {
    const double closed = 1.0 - s.world.grab(s.grab).opening_m / s.settings.max_opening_m;
    s.world.step(kDt, {&c, 1});
    if (closed * s.settings.max_depth_m < 0.5 - 0.03) {
      ASSERT_EQ(s.world.grab(s.grab).load_m3, 0.0) << n;
    }
  }
  const double triangle = s.settings.width_m * s.settings.max_depth_m * s.settings.max_opening_m / 8;
  EXPECT_NEAR(s.world.grab(s.grab).load_m3, triangle, 0.1 * triangle);
}

}  // namespace
}  // namespace harbour::bulk
