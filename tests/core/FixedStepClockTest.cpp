#include "harbour/core/FixedStepClock.h"

#include <gtest/gtest.h>

namespace harbour::core {
namespace {

TEST(FixedStepClock, CountsStepsWithoutDrift) {
  FixedStepClock clock(0.001);
  for (int n = 0; n < 1000000; ++n)
    clock.advance();
  EXPECT_DOUBLE_EQ(clock.time_s(), 1000.0);
}

TEST(FixedStepClock, DividerIsDueEveryNthStep) {
  FixedStepClock clock(0.001);
  int due = 0;
  for (int n = 0; n < 1000; ++n, clock.advance())
    due += clock.due(10);
  EXPECT_EQ(due, 100);
}

}  // namespace
}  // namespace harbour::core
