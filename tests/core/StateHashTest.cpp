#include "harbour/core/StateHash.h"

#include "harbour/core/StateArchive.h"

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

TEST(StateHash, AWriterOnAHashHashesExactlyTheBytesItWouldSave) {
  const auto save = [](StateWriter& out) {
    out.put(3.25);
    out.put(std::uint8_t{7});
    out.put(std::vector<int>{1, 2, 3});
    out.put(std::vector<double>{});
  };
  StateWriter saving;
  save(saving);
  StateHash of_bytes, hashed;
  of_bytes.add_bytes(saving.bytes().data(), saving.bytes().size());
  StateWriter hashing(hashed);
  save(hashing);
  EXPECT_EQ(hashed.value(), of_bytes.value());
  EXPECT_TRUE(hashing.bytes().empty());  // it keeps nothing
}

}  // namespace
}  // namespace harbour::core
