#include "harbour/machines/sts/StsCrane.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

#include "harbour/machines/sts/Files.h"

namespace harbour::sim {
namespace {

constexpr double kDt = 0.001;
constexpr double kG = 9.80665;

// the crane at gantry y = 0, trolley over a 40 ft container (20 t gross) along the quay at x = 20
struct Quay {
  physics::PhysicsWorld world{{}};
  StsCraneSettings settings = io::load_sts_crane(HARBOUR_DATA_DIR "/machines/sts.yaml");
  std::unique_ptr<StsCrane> crane;
  ContainerRef box;

  explicit Quay(double trolley_x_m = 20.0, double gantry_y_m = 0.0, bool rope_bending = true) {
    settings.hoist.sheaves_without_bending_loss = !rope_bending;
    world.add_ground(0.0);
    physics::BoxSettings c;
    c.half_extents_m = {12.192 / 2, 2.438 / 2, 2.591 / 2};
    c.mass_kg = 20000;
    c.pose.position = {20, 0, 2.591 / 2};
    c.pose.rotation = core::Mat3::rotation({0, 0, 1}, std::numbers::pi / 2);  // along the quay
    box = {world.add_box(c), c.half_extents_m, 11.985 / 2, 2.259 / 2};        // ISO 1161 casting centres
    crane = std::make_unique<StsCrane>(world, settings, gantry_y_m, trolley_x_m, 10.0);
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

// The spreader's swing after a trolley move decays: its eight falls roll on and off the trolley's and the
// headblock's sheaves as it swings, and their bending hysteresis (1 % of the tension per bend) takes energy
// every cycle. A swing of about 1.5 m decays by a logarithmic decrement between 0.02 and 0.3 per cycle
// (without the bending: the air's drag and the ropes' transverse damping alone, 0.001). The loss is Coulomb:
// a 4.4 m swing (the trolley stopped from half speed) loses the same metres per cycle, 0.012 of itself.
TEST(StsCrane, TheSpreadersSwingAfterATrolleyMoveDecays) {
  for (const bool bending : {true, false}) {
    Quay q(10.0, 0.0, bending);
    q.run({}, 2000);
    StsControls c;
    c.trolley = 0.2;  // a gentle trolley move and stop: a swing of about a metre
    q.run(c, 2000);
    q.run({}, 10000);
    std::vector<double> peaks;  // |spreader x - trolley x| at each turning point
    double previous = 0.0, peak = 0.0;
    for (int k = 0; k < 90000; ++k) {
      q.run({}, 1);
      const double off = q.crane->spreader_pose().position.x - q.crane->trolley_position_m();
      if ((off > 0.0) != (previous > 0.0) && peak > 0.0) peaks.push_back(std::exchange(peak, 0.0));
      peak = std::max(peak, std::abs(off));
      previous = off;
    }
    peaks.erase(peaks.begin());  // from the window's start, not a whole half cycle
    ASSERT_GE(peaks.size(), 6u);
    const double cycles = static_cast<double>(peaks.size() - 1) / 2.0;
    const double decrement = std::log(peaks.front() / peaks.back()) / cycles;
    std::printf(
        "bending %s: spreader swing %.3f m -> %.3f m over %.1f cycles, log decrement %.4f per cycle\n",
        bending ? "on" : "off", peaks.front(), peaks.back(), cycles, decrement);
    if (bending) {
      EXPECT_GT(decrement, 0.02);
      EXPECT_LT(decrement, 0.3);
    } else {
      EXPECT_LT(decrement, 0.02);
    }
  }
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
  EXPECT_NEAR(load, (q.settings.spreader.mass_kg + 20000) * kG,
              0.03 * (q.settings.spreader.mass_kg + 20000) * kG);

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
  EXPECT_EQ(q.crane->spreader_hoist().limit_hits(), 1u);
  EXPECT_EQ(q.crane->tally().limit_hits, 1u) << "the gantry and trolley stood";
}

}  // namespace
}  // namespace harbour::sim

namespace harbour::sim {
namespace {

// lowers slowly until the lamp shows landed or the spreader rests on something
bool lower_until_landed(Quay& q, const StsControls& controls) {
  StsControls lower = controls;
  lower.hoist = -0.1;
  for (int k = 0; k < 60000 && !q.crane->lamps().landed; ++k) {
    q.run(lower, 1);
    const double underside = q.crane->spreader_pose().position.z - q.crane->spreader_half_extents_m().z;
    if (underside < 2.591 + 0.05 && q.crane->hoisted_load_n() < 1000.0) break;
  }
  return q.crane->lamps().landed;
}

TEST(StsCrane, FlippersFunnelAnOffsetSpreaderOntoTheCastings) {
  // 8 cm across or 10 cm along: outside the twistlocks' 3 cm reach, inside the flippers' funnel
  StsControls flippers_down;
  flippers_down.flipper_down = {true, true, true, true};
  for (const auto& [dx, dy] : {std::pair{0.08, 0.0}, std::pair{0.0, 0.10}, std::pair{-0.07, -0.06}}) {
    Quay without(20.0 + dx, dy);
    without.run({}, 3000);
    EXPECT_FALSE(lower_until_landed(without, {})) << dx << " " << dy;

    Quay with(20.0 + dx, dy);
    with.run(flippers_down, 3500);  // the flippers swing down in 3 s
    EXPECT_EQ(with.crane->spreader_state().flippers, (std::array<double, 4>{1, 1, 1, 1}));
    ASSERT_TRUE(lower_until_landed(with, flippers_down)) << dx << " " << dy;
    StsControls lock = flippers_down;
    lock.lock = true;
    with.run(lock, 10);
    EXPECT_EQ(with.crane->locked_container(), with.box.body);
    // the flippers pushed the spreader over: it sits on the castings, off plumb under the trolley
    const core::Vec3 p = with.crane->spreader_pose().position;
    EXPECT_NEAR(p.x, 20.0, 0.03);
    EXPECT_NEAR(p.y, 0.0, 0.03);
  }
}

TEST(StsCrane, TelescopesBetweenSettingsButNotWhileLanded) {
  Quay q;
  q.run({}, 2000);
  EXPECT_NEAR(q.crane->spreader_half_extents_m().y, 12.192 / 2, 1e-12);
  StsControls twenty;
  twenty.spreader_size_ft = 20;
  q.run(twenty, 10);
  q.run({}, 5000);
  const SpreaderState moving = q.crane->spreader_state();
  EXPECT_EQ(moving.size, SpreaderSize::k20ft);
  EXPECT_TRUE(moving.telescoping);
  // each end retracts (11.985 - 5.853) / 2 = 3.066 m at 0.2 m/s: 15.3 s
  EXPECT_NEAR(moving.length_m, 2 * (11.985 / 2 - 0.2 * 5.01) + (6.058 - 5.853), 1e-9);
  q.run({}, 10200);
  EXPECT_TRUE(q.crane->spreader_state().telescoping);
  q.run({}, 300);
  EXPECT_FALSE(q.crane->spreader_state().telescoping);
  EXPECT_NEAR(q.crane->spreader_state().length_m, 6.058, 1e-9);

  // at 20 ft over a 40 ft box: the twistlocks find no castings; back to 40 ft, then landed: it may not move
  EXPECT_FALSE(lower_until_landed(q, {}));
  StsControls forty;
  forty.spreader_size_ft = 40;
  // lifted clear: the ropes first take back what the girder spans sagged while the spreader stood
  StsControls raise;
  raise.hoist = 0.3;
  const double stood_z = q.crane->spreader_pose().position.z;
  int raised_steps = 0;
  for (; raised_steps < 20000 && q.crane->spreader_pose().position.z < stood_z + 0.5; ++raised_steps)
    q.run(raise, 1);
  std::printf("lifted 0.5 m in %.1f s at 0.3 of the hoist lever\n", raised_steps * kDt);
  ASSERT_LT(raised_steps, 20000);
  q.run(forty, 16000);
  EXPECT_NEAR(q.crane->spreader_state().length_m, 12.192, 1e-9);
  ASSERT_TRUE(lower_until_landed(q, {}));
  StsControls forty_five;
  forty_five.spreader_size_ft = 45;
  q.run(forty_five, 2000);
  EXPECT_NEAR(q.crane->spreader_state().length_m, 12.192, 1e-9);
  EXPECT_EQ(q.crane->spreader_state().size, SpreaderSize::k45ft);  // selected, waits for lift-off
}

TEST(StsCrane, TheBoomLuffsOnlyWithTheTrolleyParkedAndKeepsItParkedUntilDown) {
  Quay q;  // trolley at 20 m, waterside of the 10 m park position
  StsControls up;
  up.boom = 1.0;
  q.run(up, 2000);
  EXPECT_EQ(q.crane->boom_angle_rad(), 0.0);
  StsControls landside;
  landside.trolley = -1.0;
  q.run(landside, 12000);
  ASSERT_LT(q.crane->trolley_position_m(), q.settings.boom.trolley_park_x_m);
  q.run(up, 60000);
  // 80 deg in 300 s at full lever, after a 2 s ramp: (60 - 1) s of travel
  const BoomSettings& b = q.settings.boom;
  EXPECT_NEAR(q.crane->boom_angle_rad(), b.drive.max_speed_mps * 59.0, 0.01 * b.drive.max_speed_mps * 59.0);
  // while the boom is up the trolley stops at the park position
  StsControls waterside;
  waterside.trolley = 1.0;
  q.run(waterside, 20000);
  EXPECT_LE(q.crane->trolley_position_m(), b.trolley_park_x_m + 0.01);
  EXPECT_GT(q.crane->trolley_position_m(), b.trolley_park_x_m - 0.2);
  StsControls down;
  down.boom = -1.0;
  q.run(down, 65000);
  EXPECT_EQ(q.crane->boom_angle_rad(), 0.0);
  q.run(waterside, 5000);
  EXPECT_GT(q.crane->trolley_position_m(), b.trolley_park_x_m + 5.0);
}

}  // namespace
}  // namespace harbour::sim
