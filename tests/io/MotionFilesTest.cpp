#include "harbour/io/MotionFiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "harbour/core/Units.h"
#include "scenes/DataErrors.h"

namespace harbour::io {
namespace {

std::string shipped_platform() {
  return scenes::read_text(HARBOUR_DATA_DIR "/motion/platform.yaml");
}

// one edit to the shipped platform file; the error is expected on the line holding `reported_at` (default:
// the edited line)
void expect_error(const std::string& from, const std::string& to, const std::string& field,
                  const std::string& says = "", const std::string& reported_at = "") {
  const std::string text = shipped_platform();
  scenes::expect_data_error(
      text, from, to, [](const YamlFile& f) { load_platform(f); },
      scenes::line_of(text, reported_at.empty() ? from : reported_at), field, says);
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
  expect_error("neutral_height_m: 0.90", "neutral_height_m: 1.60", "platform.neutral_height_m",
               "outside its stroke");
  expect_error("max_length_m: 1.35", "max_length_m: 1.00", "platform.neutral_height_m", "actuator 0",
               "neutral_height_m");
  expect_error("parked_heave_m: -0.18", "parked_heave_m: -0.6", "platform.sequencer.parked_heave_m");
}

TEST(MotionFiles, NonNumbersAndWrongShapesNameTheField) {
  expect_error("[-0.3090, 0.9511, 0.0]", "[-0.3090, north, 0.0]", "platform.base_joints_m[2][1]",
               "not a number");
  expect_error("[-0.3090, 0.9511, 0.0]", "[-0.3090, 0.9511]", "platform.base_joints_m[2]");
  expect_error("roll_deg_s: 30", "roll_deg_s: .inf", "platform.max_velocity.roll_deg_s");
  expect_error("min_length_m: 0.90", "min_length_m: 1.40", "platform.max_length_m", "must exceed",
               "max_length_m");
}

TEST(MotionFiles, UnknownMachineIsAnError) {
  EXPECT_THROW(load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml", "hovercraft"), DataError);
}

}  // namespace
}  // namespace harbour::io
