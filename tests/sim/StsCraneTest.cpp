#include "harbour/sim/StsCrane.h"

#include <gtest/gtest.h>

#include "harbour/io/MachineFiles.h"

namespace harbour::sim {
namespace {

constexpr double kDt = 0.001;
constexpr double kG = 9.80665;

// the crane at gantry y = 0, trolley over a 40 ft container (20 t gross) standing on the quay at x = 20
struct Quay {
  physics::PhysicsWorld world{{}};
  StsCraneSettings settings = io::load_sts_crane(HARBOUR_DATA_DIR "/machines/sts.yaml");
  std::unique_ptr<StsCrane> crane;
  ContainerRef box;

  Quay() {
    world.add_ground(0.0);
    physics::BoxSettings c;
    c.half_extents_m = {12.192 / 2, 2.438 / 2, 2.591 / 2};
    c.mass_kg = 20000;
    c.pose.position = {20, 0, 2.591 / 2};
    box = {world.add_box(c), c.half_extents_m};
    crane = std::make_unique<StsCrane>(world, settings, 0.0, 20.0, 10.0);
  }
  void run(const StsControls& c, int steps) {
    for (int k = 0; k < steps; ++k) {
      crane->step(c, {&box, 1}, kDt);
      world.step(kDt);
    }
  }
  double container_z() const { return world.pose(box.body).position.z; }
};

TEST(StsCrane, TrolleyFollowsItsDrive) {
  Quay q;
  q.run({}, 2000);
  StsControls c;
  c.trolley = 1.0;
  q.run(c, 5000);
  // 0.6 m/s^2 for 5 s: 7.5 m
  EXPECT_NEAR(q.crane->trolley_position_m(), 27.5, 0.02);
  EXPECT_NEAR(q.crane->gantry_position_m(), 0.0, 1e-6);
}

TEST(StsCrane, HoistRaisesTheSpreaderAtHalfTheRopeSpeed) {
  Quay q;
  q.run({}, 3000);
  const double z0 = q.crane->spreader_pose().position.z;
  StsControls c;
  c.hoist = 1.0;
  q.run(c, 6000);
  q.run({}, 4000);  // the drum ramps down and brakes; the bounce dies
  // rope reeled: ramp to 3 m/s at 1 m/s^2 (4.5 m in 3 s), 3 s at 3 m/s (9 m), ramp down (4.5 m): 18 m on 2
  // falls
  EXPECT_NEAR(q.crane->spreader_pose().position.z - z0, 18.0 / 2, 0.02 * 9.0);
}

TEST(StsCrane, PicksUpAndSetsDownAContainer) {
  Quay q;
  q.run({}, 2000);
  StsControls lower;
  lower.hoist = -0.1;
  int steps = 0;
  while (!q.crane->lamps().landed && steps++ < 60000)
    q.run(lower, 1);
  ASSERT_TRUE(q.crane->lamps().landed) << "spreader at " << q.crane->spreader_pose().position.z;
  q.run({}, 500);
  StsControls lock;
  lock.lock = true;
  q.run(lock, 10);
  ASSERT_EQ(q.crane->locked_container(), q.box.body);

  StsControls hoist;
  hoist.hoist = 0.3;
  q.run(hoist, 6000);
  q.run({}, 4000);
  EXPECT_GT(q.container_z() - 2.591 / 2, 1.0);
  // the hoist now carries spreader and container: mean over a second of the bounce
  double load = 0;
  for (int k = 0; k < 1000; ++k) {
    q.run({}, 1);
    load += q.crane->hoisted_load_n() / 1000;
  }
  EXPECT_NEAR(load, (q.settings.spreader_mass_kg + 20000) * kG,
              0.03 * (q.settings.spreader_mass_kg + 20000) * kG);

  // unlocking in the air is refused
  StsControls unlock;
  unlock.unlock = true;
  q.run(unlock, 10);
  EXPECT_EQ(q.crane->locked_container(), q.box.body);
  auto events = q.crane->take_twistlock_events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0], TwistlockEvent::kUnlockRefusedSuspended);

  // set down, unlock, lift away: the container stays
  q.run({}, 10);
  steps = 0;
  while (q.container_z() > 2.591 / 2 + 0.005 && steps++ < 60000)
    q.run(lower, 1);
  q.run(lower, 1000);  // keep lowering until the ropes slacken: the ground carries the box
  q.run({}, 1000);
  q.run(unlock, 10);
  EXPECT_FALSE(q.crane->locked_container().has_value());
  q.run(hoist, 3000);
  EXPECT_NEAR(q.container_z(), 2.591 / 2, 0.01);
  EXPECT_TRUE(q.crane->take_twistlock_events().empty());
}

TEST(StsCrane, LockIsRefusedInTheAir) {
  Quay q;
  q.run({}, 1000);
  StsControls lock;
  lock.lock = true;
  q.run(lock, 10);
  EXPECT_FALSE(q.crane->locked_container().has_value());
  auto events = q.crane->take_twistlock_events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0], TwistlockEvent::kLockRefusedNotLanded);
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

TEST(StsCrane, HoistStopsOnItsUpperLimitSwitch) {
  Quay q;
  q.run({}, 1000);
  StsControls up;
  up.hoist = 1.0;
  q.run(up, 40000);  // keep pushing up for 40 s
  const double z = q.crane->spreader_pose().position.z;
  EXPECT_LE(z, q.settings.hoist_upper_limit_m + 0.05);
  EXPECT_GE(z, q.settings.hoist_upper_limit_m - 0.1);
  EXPECT_EQ(q.crane->hoist_limit_hits(), 1u);
}

}  // namespace
}  // namespace harbour::sim
