#include "harbour/core/StateHash.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace harbour::core {
namespace {

TEST(StateHash, KnownFnv1aValue) {
  StateHash h;
  h.add_bytes("a", 1);
  EXPECT_EQ(h.value(), 0xAF63DC4C8601EC8Cull);  // published FNV-1a 64 of "a"
}

TEST(StateHash, OneBitChangesTheHash) {
  std::vector<double> v(100, 1.0);
  StateHash a, b;
  a.add(std::span<const double>(v));
  v[57] = std::nextafter(1.0, 2.0);
  b.add(std::span<const double>(v));
  EXPECT_NE(a.value(), b.value());
}

}  // namespace
}  // namespace harbour::core
