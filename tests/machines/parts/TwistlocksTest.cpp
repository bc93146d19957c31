#include "harbour/machines/parts/Twistlocks.h"

#include <gtest/gtest.h>

#include "harbour/core/Units.h"

namespace harbour::sim {
namespace {

constexpr double kHalfLength40 = 12.192 / 2, kHalfWidth = 2.438 / 2;  // ISO 668, 40 ft
constexpr std::array<bool, 4> kAll{true, true, true, true};

core::Pose at(double x, double y, double z, double yaw_deg = 0.0) {
  core::Pose p;
  p.rotation = core::Mat3::rotation({0, 0, 1}, core::deg_to_rad(yaw_deg));
  p.position = {x, y, z};
  return p;
}

std::array<bool, 4> landed_40ft(const core::Pose& underside, const core::Pose& top,
                                const TwistlockSettings& s) {
  return landed_corners(underside, kHalfLength40, kHalfWidth, top, kHalfLength40, kHalfWidth, s);
}

TEST(Twistlocks, LandedOnlyWithinTheCastingTolerances) {
  const core::Pose container = at(10, 5, 2.591);
  const TwistlockSettings s;
  EXPECT_EQ(landed_40ft(at(10.02, 5.0, 2.595), container, s), kAll);
  EXPECT_EQ(landed_40ft(at(10.05, 5.0, 2.591), container, s),
            (std::array<bool, 4>{false, false, false, false}));  // 5 cm off: outside the cones' reach
  EXPECT_EQ(landed_40ft(at(10, 5, 2.62), container, s),
            (std::array<bool, 4>{false, false, false, false}));  // still 3 cm above
  // skewed 0.4 degrees: the far ends move 4 cm sideways, outside the tolerance
  const auto skewed = landed_40ft(at(10, 5, 2.591, 0.4), container, s);
  EXPECT_FALSE(skewed[0] && skewed[1] && skewed[2] && skewed[3]);
}

TEST(Twistlocks, TheSpreaderSetToAnotherLengthFindsNoCastings) {
  // ISO 1161 casting centres: 20 ft 5.853 m, 40 ft 11.985 m apart; a spreader at 20 ft over a 40 ft box
  // puts its twistlocks on the roof, 3 m from the castings
  const core::Pose container = at(10, 5, 2.591);
  const TwistlockSettings s;
  const std::array<bool, 4> none{false, false, false, false};
  EXPECT_EQ(landed_corners(container, 5.853 / 2, 2.259 / 2, container, 11.985 / 2, 2.259 / 2, s), none);
  EXPECT_EQ(landed_corners(container, 11.985 / 2, 2.259 / 2, container, 11.985 / 2, 2.259 / 2, s), kAll);
  // telescoping and 2.5 cm short of the 40 ft setting: within the cones' reach; 4 cm short: not
  EXPECT_EQ(landed_corners(container, 11.96 / 2, 2.259 / 2, container, 11.985 / 2, 2.259 / 2, s), kAll);
  EXPECT_EQ(landed_corners(container, 11.905 / 2, 2.259 / 2, container, 11.985 / 2, 2.259 / 2, s), none);
}

constexpr double kStep_s = 0.001;

// Holds the sensors and buttons for a while (the landing logic debounces lift-offs).
void hold(Twistlocks& t, const std::array<bool, 4>& landed, bool load_suspended, double seconds) {
  for (double s = 0.0; s < seconds; s += kStep_s)
    t.update(landed, false, false, load_suspended, kStep_s);
}

TEST(Twistlocks, LockOnlyWhenAllFourAreLanded) {
  Twistlocks t;
  t.update({true, true, true, false}, true, false, false, kStep_s);
  EXPECT_FALSE(t.locked());
  EXPECT_EQ(t.take_events(), std::vector<TwistlockEvent>{TwistlockEvent::kLockRefusedNotLanded});
  t.update(kAll, false, false, false, kStep_s);
  t.update(kAll, true, false, false, kStep_s);
  EXPECT_TRUE(t.locked());
  EXPECT_TRUE(t.lamps().landed);
  EXPECT_TRUE(t.lamps().locked);
  EXPECT_FALSE(t.lamps().unlocked);
}

TEST(Twistlocks, NeverUnlockUnderLoad) {
  Twistlocks t;
  t.update(kAll, true, false, false, kStep_s);
  t.update({false, false, false, false}, false, false, true, kStep_s);  // lifted with the container
  t.update({false, false, false, false}, false, true, true, kStep_s);   // unlock in the air
  EXPECT_TRUE(t.locked());
  EXPECT_EQ(t.take_events(), std::vector<TwistlockEvent>{TwistlockEvent::kUnlockRefusedSuspended});
}

TEST(Twistlocks, ASetDownIsNormalButAnUnlockedPickUpIsMisuse) {
  Twistlocks t;
  // pick-up done right, move, set down, unlock, lift away: no events
  t.update(kAll, true, false, false, kStep_s);
  hold(t, {false, false, false, false}, true, 1.0);
  t.update(kAll, false, false, false, kStep_s);
  t.update(kAll, false, true, false, kStep_s);
  // the seated sensors flicker as the released spreader settles on the box, then it lifts away
  hold(t, {false, false, false, false}, false, 0.02);
  hold(t, kAll, false, 0.3);
  hold(t, {false, false, false, false}, false, 1.0);
  EXPECT_TRUE(t.take_events().empty());
  // arrive empty on the next box and hoist without locking
  hold(t, kAll, false, 0.5);
  hold(t, {false, false, false, false}, false, 1.0);
  EXPECT_EQ(t.take_events(), std::vector<TwistlockEvent>{TwistlockEvent::kHoistedUnlocked});
}

}  // namespace
}  // namespace harbour::sim
