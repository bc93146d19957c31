#include "harbour/station/LookAround.h"

#include <gtest/gtest.h>

#include <cmath>

namespace harbour::station {
namespace {

// Keys turn the view at a head's pace within the cab's limits; a drag turns it with the hand; let go, it
// eases back to the line of sight.
TEST(LookAround, KeysTurnAtAHeadsPaceWithinTheLimitsAndLetGoItEasesBack) {
  LookAround look({1.0, 0.5});
  for (int n = 0; n < 10; ++n)  // 0.5 s of keypad 4 (left) and 8 (up)
    look.update(0.05, 1, 1, 0.0, 0.0, false);
  EXPECT_NEAR(look.yaw_rad(), 0.5 * LookAround::kTurn_radps, 1e-9);
  EXPECT_NEAR(look.pitch_rad(), 0.5, 1e-9);  // at its limit
  for (int n = 0; n < 20; ++n)               // another second: the yaw stops at its limit too
    look.update(0.05, 1, 0, 0.0, 0.0, false);
  EXPECT_NEAR(look.yaw_rad(), 1.0, 1e-9);
  // let go: after one time constant a third is left, after a second almost nothing
  look.update(LookAround::kEaseBack_s, 0, 0, 0.0, 0.0, false);
  EXPECT_NEAR(look.yaw_rad(), std::exp(-1.0), 1e-9);
  for (int n = 0; n < 20; ++n)
    look.update(0.05, 0, 0, 0.0, 0.0, false);
  EXPECT_LT(std::abs(look.yaw_rad()), 0.02);
  // a drag to the right and down turns right and down, and holds while the button is held
  LookAround drag({2.0, 1.0});
  drag.update(0.02, 0, 0, 100.0, 50.0, true);
  EXPECT_NEAR(drag.yaw_rad(), -100.0 * LookAround::kDrag_rad_per_px, 1e-12);
  EXPECT_NEAR(drag.pitch_rad(), -50.0 * LookAround::kDrag_rad_per_px, 1e-12);
  drag.update(1.0, 0, 0, 0.0, 0.0, true);
  EXPECT_NEAR(drag.yaw_rad(), -100.0 * LookAround::kDrag_rad_per_px, 1e-12);
  drag.recentre();
  EXPECT_EQ(drag.yaw_rad(), 0.0);
}

}  // namespace
}  // namespace harbour::station
