#include "harbour/core/Rng.h"

#include <gtest/gtest.h>

namespace harbour::core {
namespace {

TEST(Rng, SameSeedSameSequence) {
  Rng a(42), b(42), c(43);
  bool differs = false;
  for (int n = 0; n < 1000; ++n) {
    const auto x = a.next_u64();
    EXPECT_EQ(x, b.next_u64());
    differs |= x != c.next_u64();
  }
  EXPECT_TRUE(differs);
}

TEST(Rng, UniformIsInRangeWithMeanOneHalf) {
  Rng rng(7);
  double sum = 0;
  for (int n = 0; n < 100000; ++n) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  EXPECT_NEAR(sum / 100000, 0.5, 0.005);
}

}  // namespace
}  // namespace harbour::core
