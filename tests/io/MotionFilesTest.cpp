#include "harbour/io/MotionFiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "harbour/core/Units.h"

namespace harbour::io {
namespace {

std::string shipped_platform() {
  std::ifstream in(HARBOUR_DATA_DIR "/motion/platform.yaml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

// replaces `from` by `to` and expects an error for `field` on the line holding `reported_at` (default: `to`)
void expect_error(std::string text, const std::string& from, const std::string& to, const std::string& field,
                  const std::string& says = "", const std::string& reported_at = "") {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  try {
    load_platform(YamlFile::parse(text, "platform.yaml"));
    FAIL() << "accepted " << to;
  } catch (const DataError& e) {
    EXPECT_EQ(e.line(), line_of(text, reported_at.empty() ? to : reported_at)) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(MotionFiles, ShippedPlatformAndWashoutLoad) {
  const PlatformFile p = load_platform(HARBOUR_DATA_DIR "/motion/platform.yaml");
  EXPECT_EQ(p.name, "generic_6dof");
  EXPECT_DOUBLE_EQ(p.limits.max_acceleration[motion::kRoll], core::deg_to_rad(300.0));
  const auto sts = load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml", "sts");
  EXPECT_DOUBLE_EQ(sts.surge_sway.gain, 0.35);
  EXPECT_DOUBLE_EQ(sts.surge_sway.wn_rad_s, 1.25);  // from the defaults
}

TEST(MotionFiles, ActuatorsThatCannotReachNeutralAreRejected) {
  expect_error(shipped_platform(), "neutral_height_m: 0.90", "neutral_height_m: 1.60",
               "platform.neutral_height_m", "outside its stroke");
  expect_error(shipped_platform(), "max_length_m: 1.35", "max_length_m: 1.00", "platform.neutral_height_m",
               "actuator 0", "neutral_height_m");
  expect_error(shipped_platform(), "parked_heave_m: -0.18", "parked_heave_m: -0.6",
               "platform.sequencer.parked_heave_m");
}

TEST(MotionFiles, NonNumbersAndWrongShapesNameTheField) {
  expect_error(shipped_platform(), "[-0.3090, 0.9511, 0.0]", "[-0.3090, north, 0.0]",
               "platform.base_joints_m[2][1]", "not a number");
  expect_error(shipped_platform(), "[-0.3090, 0.9511, 0.0]", "[-0.3090, 0.9511]",
               "platform.base_joints_m[2]");
  expect_error(shipped_platform(), "roll_deg_s: 30", "roll_deg_s: .inf", "platform.max_velocity.roll_deg_s");
  expect_error(shipped_platform(), "min_length_m: 0.90", "min_length_m: 1.40", "platform.max_length_m",
               "must exceed", "max_length_m");
}

TEST(MotionFiles, UnknownMachineIsAnError) {
  EXPECT_THROW(load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml", "hovercraft"), DataError);
}

}  // namespace
}  // namespace harbour::io
