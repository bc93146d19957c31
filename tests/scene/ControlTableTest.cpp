// A machine's control table on its own: what it refuses, where its controls sit, and how it reads values.
#include "harbour/scene/Controls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "support/ControlSpecs.h"

namespace harbour::scene {
namespace {

using test::axis;
using test::button;
using test::selector;

void expect_refused(std::vector<ControlSpec> controls, const std::string& says) {
  try {
    ControlTable table(std::move(controls));
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(ControlTable, RefusesWhatNoMachineCouldReadNamingTheControl) {
  expect_refused({axis("hoist"), axis("hoist")}, "control 'hoist' is declared twice");
  expect_refused({axis("")}, "control 1 has no label");
  expect_refused({axis("trolley", 1.0, 1.0)}, "control 'trolley': an axis needs min < max");
  expect_refused({selector("gear", {"N"}, 0.0)}, "control 'gear': a switch has at least two positions");
  ControlSpec pedal = axis("brake", 0.0, 1.0);
  pedal.neutral = -0.5;
  expect_refused({pedal}, "control 'brake': neutral and safe values must be values it can take");
  std::vector<ControlSpec> many;
  for (int n = 0; n <= kMaxControls; ++n)
    many.push_back(axis(("a" + std::to_string(n)).c_str()));
  expect_refused(many, "at most 32 controls");
}

TEST(ControlTable, FindsSlotsByLabelAndKind) {
  const ControlTable table({axis("hoist"), button("lock"), selector("gear", {"R", "N", "D"}, 1.0)});
  EXPECT_EQ(table.size(), 3);
  EXPECT_EQ(table.find("lock"), 1);
  EXPECT_EQ(table.find("horn"), -1);
  EXPECT_EQ(table.slot("gear", ControlKind::kSwitch), 2);
  try {
    table.slot("lock", ControlKind::kAxis);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "control 'lock' must be a axis, not a button");
  }
  EXPECT_THROW(table.slot("horn", ControlKind::kButton), std::invalid_argument);
  EXPECT_EQ(table.neutral().value[2], 1.0) << "the gear at rest in N";
}

// What a device sends is read as the machine can take it: an axis clamped, a button 0 or 1, a switch at a
// whole position; a non-finite value (a device or link fault) reads as the control at rest.
TEST(ControlTable, ReadsEveryValueIntoItsControlsRange) {
  const ControlTable table(
      {axis("throttle", 0.0, 1.0), button("horn"), selector("gear", {"R", "N", "D"}, 1.0)});
  Controls raw;
  raw.value = {1.7, 0.3, 2.6};
  raw.value[5] = 9.0;  // a slot the machine does not use
  Controls read = table.in_range(raw);
  EXPECT_EQ(read.value[0], 1.0);
  EXPECT_EQ(read.value[1], 1.0);
  EXPECT_EQ(read.value[2], 2.0);
  EXPECT_EQ(read.value[5], 0.0);
  raw.value = {-3.0, 0.0, -1.4};
  read = table.in_range(raw);
  EXPECT_EQ(read.value[0], 0.0);
  EXPECT_EQ(read.value[1], 0.0);
  EXPECT_EQ(read.value[2], 0.0);
  raw.value = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
               std::numeric_limits<double>::quiet_NaN()};
  read = table.in_range(raw);
  EXPECT_EQ(read.value[0], 0.0);
  EXPECT_EQ(read.value[1], 0.0);
  EXPECT_EQ(read.value[2], 1.0) << "a faulted gear selector reads N, not R";
}

}  // namespace
}  // namespace harbour::scene
