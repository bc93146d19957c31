#include "harbour/bulk/BulkWorld.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "harbour/core/Rng.h"
#include "scenes/BulkScenes.h"

namespace harbour::bulk {
namespace {

// a yard grid and a rolling hold beside it; a grab shuttles between them while a conveyor pours
struct ShuttleScene {
  BulkWorld world{scenes::test_material(35.0), [] {
                    BulkWorldSettings s;
                    s.spill_level_m = -3.0;
                    return s;
                  }()};
  int yard = world.add_grid({80, 80, 0.1}, {});
  int hold = world.add_grid({60, 40, 0.1}, [] {
    core::Pose p;
    p.position = {12.0, 2.0, -2.0};
    return p;
  }());
  int grab = world.add_grab(GrabSettings{.width_m = 1.2,
                                         .max_opening_m = 1.6,
                                         .max_depth_m = 0.6,
                                         .sinking_speed_mps = 0.3,
                                         .spill_speed_mps = 2.0,
                                         .capacity_m3 = 1.0,
                                         .closing_time_s = 2.0});
  GrabCommand command = scenes::grab_at({4.0, 4.0, 3.0}, -1.0);

  void step(long n) {
    // hold rolls 3 degrees with a 10 s period about its centre line
    const double t = static_cast<double>(n) * 0.001, w = 2 * std::numbers::pi / 10.0;
    core::Pose p;
    p.rotation = core::Mat3::rotation({1, 0, 0}, 0.052 * std::sin(w * t));
    p.position = {12.0, 2.0, -2.0};
    world.grid(hold).set_pose(p, {}, {0.052 * w * std::cos(w * t), 0, 0});

    // a 20 s cycle: conveyor pours for 5 s, the grab bites, lifts, swings out over the hold (and once
    // in three cycles stops short over the quay edge so part of the drop is spilled), opens
    const long phase = n % 20000;
    if (phase < 5000) world.pour(yard, 4.0, 4.0, 0.0004);
    const GrabState& g = world.grab(grab);
    if (phase < 7000) {
      command.pose.position = {
          4.0, 4.0,
          std::max(world.grid(yard).surface_height(4.0, 4.0) + 0.3 - static_cast<double>(phase) * 1e-4,
                   -1.0)};
      command.close_rate = -1.0;
    } else if (phase < 9500) {
      command.close_rate = 1.0;
      if (g.digging) command.pose.position.z -= 0.3 * 0.001;
    } else if (phase < 14000) {
      command.close_rate = 0.0;
      const bool short_swing = (n / 20000) % 3 == 2;
      command.pose.position = {short_swing ? 10.0 : 15.0, 4.0, 3.0};
    } else {
      command.close_rate = -1.0;
    }
    world.step(0.001, {&command, 1});
  }
};

TEST(BulkWorld, MassIsConservedOverAHundredThousandSteps) {
  ShuttleScene scene;
  double worst = 0.0;
  for (long n = 0; n < 100000; ++n) {
    scene.step(n);
    if (n % 997 == 0) worst = std::max(worst, std::abs(scene.world.balance().discrepancy_m3()));
  }
  const VolumeBalance b = scene.world.balance();
  // every path was exercised: material moved, was held, fell into the hold, and spilled
  EXPECT_NEAR(b.added_m3, 10.0, 1e-9);
  EXPECT_GT(scene.world.grid(scene.hold).total_volume_m3(), 1.0);
  EXPECT_GT(b.spilled_m3, 0.1);
  EXPECT_GT(scene.world.loaded_m3(), 2.5);
  EXPECT_LT(worst, 1e-11 * b.added_m3);
  EXPECT_LT(std::abs(b.discrepancy_m3()), 1e-11 * b.added_m3);
  EXPECT_EQ(scene.world.warnings().total(), 0u);
}

TEST(BulkWorld, SameInputsGiveTheSameStateHash) {
  ShuttleScene a, b;
  for (long n = 0; n < 30000; ++n) {
    a.step(n);
    b.step(n);
  }
  EXPECT_EQ(a.world.state_hash(), b.world.state_hash());
  b.step(30000);
  EXPECT_NE(a.world.state_hash(), b.world.state_hash());
}

TEST(BulkWorld, FallingMaterialLandsOnTheGridBelowOrIsSpilled) {
  BulkWorld world(scenes::test_material(), BulkWorldSettings{.spill_level_m = -1.0});
  const int g = world.add_grid({20, 20, 0.1}, {});
  const int grab = world.add_grab({});
  world.pour(g, 1.0, 1.0, 0.5);
  // dig the pile, then open 3 m above the grid, then open far outside it
  GrabCommand c = scenes::grab_at({1.0, 1.0, 0.0}, 1.0);
  for (int n = 0; n < 6000; ++n)
    world.step(0.001, {&c, 1});
  const double held = world.grab(grab).load_m3;
  ASSERT_GT(held, 0.1);
  c = scenes::grab_at({1.0, 1.0, 3.0}, -1.0);
  for (int n = 0; n < 3000; ++n)
    world.step(0.001, {&c, 1});
  EXPECT_EQ(world.balance().spilled_m3, 0.0);
  EXPECT_TRUE(world.parcels().empty());
  EXPECT_NEAR(world.grid(g).total_volume_m3(), 0.5, 1e-12);
}

}  // namespace
}  // namespace harbour::bulk

namespace harbour::bulk {
namespace {

TEST(BulkWorld, AKeyframeContinuesBitForBit) {
  // mid-cycle: the grab carrying a bite over the hold, parcels in the air, the pile still flowing
  ShuttleScene a;
  for (long n = 0; n < 14500; ++n)
    a.step(n);
  ASSERT_FALSE(a.world.parcels().empty());
  core::StateWriter out;
  a.world.save_state(out);
  const std::vector<std::uint8_t> keyframe = out.take();
  ShuttleScene b;
  core::StateReader in(keyframe);
  b.world.restore_state(in);
  EXPECT_TRUE(in.at_end());
  b.command = a.command;  // the scene's own state: where the grab is commanded
  EXPECT_EQ(b.world.state_hash(), a.world.state_hash());
  for (long n = 14500; n < 30000; ++n) {
    a.step(n);
    b.step(n);
  }
  EXPECT_EQ(b.world.state_hash(), a.world.state_hash());
  EXPECT_EQ(b.world.balance().spilled_m3, a.world.balance().spilled_m3);
  // a world of other grids refuses it, changing nothing
  BulkWorld other(scenes::test_material(35.0), BulkWorldSettings{});
  other.add_grid({40, 40, 0.1}, {});
  core::StateReader again(keyframe);
  EXPECT_THROW(other.restore_state(again), core::StateError);
}

}  // namespace
}  // namespace harbour::bulk

namespace harbour::bulk {
namespace {

TEST(BulkWorld, AHopperDeliversWhatFallsInAtItsOutletsRate) {
  // a 6 m hopper with a 20 m^3 heap in it, drained at 0.5 m^3/s: 5 m^3 in 10 s, then empty after 40 s
  BulkWorld world(scenes::test_material(35.0), BulkWorldSettings{});
  const int hopper = world.add_grid({30, 30, 0.2}, {});
  const double heap = world.add_heap(hopper, 3.0, 3.0, 20.0);
  world.set_outflow(hopper, 0.5);
  for (int k = 0; k < 10000; ++k)
    world.step(0.001, {});
  EXPECT_NEAR(world.balance().delivered_m3, 5.0, 1e-9);
  EXPECT_NEAR(world.balance().discrepancy_m3(), 0.0, 1e-9);
  for (int k = 0; k < 35000; ++k)
    world.step(0.001, {});
  EXPECT_NEAR(world.balance().delivered_m3, heap, 1e-6);  // all of it, no more
  EXPECT_LT(world.grid(hopper).total_volume_m3(), 1e-6);
  EXPECT_NEAR(world.balance().discrepancy_m3(), 0.0, 1e-9);
}

}  // namespace
}  // namespace harbour::bulk
