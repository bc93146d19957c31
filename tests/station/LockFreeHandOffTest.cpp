// The station's two lock-free hand-offs between threads, tested directly: the bounded queue the instructor's
// commands and device events cross (SpscRing) and the latest-value buffer the snapshots cross (TripleBuffer).
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <thread>

#include "harbour/station/SpscRing.h"
#include "harbour/station/TripleBuffer.h"

namespace harbour::station {
namespace {

TEST(SpscRing, HoldsExactlyItsCapacityInOrderAcrossTheWrap) {
  SpscRing<int> ring(3);
  EXPECT_TRUE(ring.empty());
  int out = -1;
  EXPECT_FALSE(ring.pop(out));
  for (int round = 0; round < 5; ++round) {  // the indices wrap several times
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(ring.push(10 * round + k));
    EXPECT_FALSE(ring.push(99)) << "a full ring refuses, nothing changed";
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(ring.pop(out));
      EXPECT_EQ(out, 10 * round + k);
    }
    EXPECT_TRUE(ring.empty());
  }
}

// One producer, one consumer, a million items through a ring of 8: every item arrives once, in order.
TEST(SpscRing, AProducerAndAConsumerThreadLoseAndReorderNothing) {
  constexpr std::uint64_t kItems = 1'000'000;
  SpscRing<std::uint64_t> ring(8);
  std::thread producer([&] {
    for (std::uint64_t n = 1; n <= kItems; ++n)
      while (!ring.push(n))
        std::this_thread::yield();
  });
  std::uint64_t expected = 1, got = 0, out_of_order = 0;
  while (expected <= kItems) {
    if (!ring.pop(got)) {
      std::this_thread::yield();
      continue;
    }
    if (got != expected) ++out_of_order;
    expected = got + 1;
  }
  producer.join();
  EXPECT_EQ(out_of_order, 0u);
  EXPECT_EQ(got, kItems);
  EXPECT_TRUE(ring.empty());
}

TEST(TripleBuffer, TheReaderSeesNothingBeforeTheFirstValueThenTheNewest) {
  TripleBuffer<int> buffer;
  EXPECT_EQ(buffer.latest(), nullptr);
  buffer.back() = 1;
  buffer.publish();
  buffer.back() = 2;
  buffer.publish();  // the reader has not looked: 1 is overwritten, never seen
  ASSERT_NE(buffer.latest(), nullptr);
  EXPECT_EQ(*buffer.latest(), 2);
  EXPECT_EQ(*buffer.latest(), 2) << "stable until something newer is published";
  buffer.back() = 3;
  EXPECT_EQ(*buffer.latest(), 2) << "filling back() publishes nothing";
  buffer.publish();
  EXPECT_EQ(*buffer.latest(), 3);
}

// A writer publishing whole records as fast as it can, a reader looking at its own pace: every record the
// reader sees is whole (all its fields from one publish) and never older than the one it saw before.
TEST(TripleBuffer, AReaderThreadSeesOnlyWholeValuesNeverGoingBack) {
  struct Record {
    std::array<std::uint64_t, 64> fields{};
  };
  constexpr std::uint64_t kRecords = 200'000;
  TripleBuffer<Record> buffer;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (std::uint64_t n = 1; n <= kRecords; ++n) {
      buffer.back().fields.fill(n);
      buffer.publish();
    }
    done = true;
  });
  std::uint64_t last = 0, torn = 0, backwards = 0, looks = 0;
  while (!done || last < kRecords) {
    const Record* r = buffer.latest();
    if (!r) continue;
    ++looks;
    const std::uint64_t n = r->fields[0];
    for (std::uint64_t f : r->fields)
      if (f != n) ++torn;
    if (n < last) ++backwards;
    last = n;
  }
  writer.join();
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(backwards, 0u);
  EXPECT_EQ(last, kRecords) << "the last value published is the last seen";
  EXPECT_GT(looks, 0u);
}

}  // namespace
}  // namespace harbour::station
