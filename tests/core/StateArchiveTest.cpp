#include "harbour/core/StateArchive.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace harbour::core {
namespace {

// A part and its owner written as the classes of the simulation write theirs: one archive template each.
class Counter {
 public:
  void count() { ++hits_; }
  std::uint32_t hits() const { return hits_; }
  void save_state(StateWriter& out) const { archive(*this, out); }
  void restore_state(StateReader& in) { archive(*this, in); }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar(self.hits_);
  }
  std::uint32_t hits_ = 0;
};

class Axis {
 public:
  explicit Axis(std::size_t cells) : cells_(cells, 0.0) {}
  double position = 0.0;
  bool braked = false;
  std::vector<double> cells_;  // as long as the scenario makes it
  std::vector<int> events;     // any length
  Counter limit;
  int restores = 0;  // what only a restore does
  void save_state(StateWriter& out) const { archive(*this, out); }
  void restore_state(StateReader& in) {
    archive(*this, in);
    ++restores;
  }

 private:
  template <typename Self, typename Archive>
  static void archive(Self& self, Archive& ar) {
    ar.section(0x41584953, "axis");
    ar(self.position, self.braked);
    ar.sized(self.cells_);
    ar(self.events);
    ar.part(self.limit);
    if constexpr (Archive::kRestoring)
      if (self.position < 0.0) throw StateError("saved axis is behind its end stop");
  }
};

TEST(StateArchive, OneListSavesAndRestoresEveryField) {
  Axis a(3);
  a.position = 2.5;
  a.braked = true;
  a.cells_ = {1.0, 2.0, 3.0};
  a.events = {4, 5};
  a.limit.count();
  StateWriter out;
  a.save_state(out);

  Axis b(3);
  StateReader in(out.bytes());
  b.restore_state(in);
  EXPECT_TRUE(in.at_end());
  EXPECT_EQ(b.position, 2.5);
  EXPECT_TRUE(b.braked);
  EXPECT_EQ(b.cells_, a.cells_);
  EXPECT_EQ(b.events, a.events);
  EXPECT_EQ(b.limit.hits(), 1u);
  EXPECT_EQ(b.restores, 1);
}

TEST(StateArchive, TheBytesAreThoseOfTheFieldsInOrder) {
  Axis a(1);
  a.position = 1.5;
  a.cells_ = {7.0};
  StateWriter archived;
  a.save_state(archived);
  StateWriter by_hand;
  by_hand.section(0x41584953);
  by_hand.put(1.5);
  by_hand.put(false);
  by_hand.put(std::vector<double>{7.0});
  by_hand.put(std::vector<int>{});
  by_hand.put(std::uint32_t{0});
  EXPECT_EQ(archived.bytes(), by_hand.bytes());
}

TEST(StateArchive, ARestoreRefusesAnotherSizeATagOrAValueItChecks) {
  Axis a(3);
  StateWriter out;
  a.save_state(out);
  Axis longer(4);
  StateReader in(out.bytes());
  EXPECT_THROW(longer.restore_state(in), StateError);

  StateWriter other;
  other.section(0x42414420);
  Axis b(3);
  StateReader tagged(other.bytes());
  try {
    b.restore_state(tagged);
    FAIL() << "another section's tag was read";
  } catch (const StateError& e) {
    EXPECT_NE(std::string(e.what()).find("axis section"), std::string::npos) << e.what();
  }

  a.position = -1.0;
  StateWriter behind;
  a.save_state(behind);
  StateReader checked(behind.bytes());
  EXPECT_THROW(b.restore_state(checked), StateError);
}

}  // namespace
}  // namespace harbour::core
