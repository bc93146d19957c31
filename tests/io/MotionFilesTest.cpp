#include "harbour/io/MotionFiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "harbour/core/Units.h"
#include "harbour/machines/sts/Files.h"
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
  const auto sts =
      load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml", HARBOUR_DATA_DIR "/machines/sts.yaml");
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

TEST(MotionFiles, AMachinesBadMotionCuesAreNamedByFileLineAndField) {
  const auto error = [](const std::string& cues) {
    try {
      check_motion_cues(YamlFile::parse("machine: {kind: sts}\nmotion_cues:\n" + cues, "crane.yaml"));
    } catch (const DataError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("  tilt: {gain: 0.4}\n"), "accepted");
  EXPECT_NE(error("  tilt: {gain: -0.4}\n").find("crane.yaml:3"), std::string::npos)
      << error("  tilt: {gain: -0.4}\n");
  EXPECT_NE(error("  tilt: {gain: -0.4}\n").find("motion_cues.tilt.gain"), std::string::npos);
  // a misspelt key: the machine's loader reads its whole file, motion cues and all
  std::ifstream in(HARBOUR_DATA_DIR "/machines/sts.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string misspelt = text.str();
  misspelt.replace(misspelt.find("surge_sway: {gain: 0.35}"), 24, "surge_sway: {gian: 0.35}");
  try {
    load_sts_crane(YamlFile::parse(misspelt, "sts.yaml"), HARBOUR_DATA_DIR "/machines");
    ADD_FAILURE() << "a misspelt motion cue was accepted";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("motion_cues.surge_sway"), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      load_washout(HARBOUR_DATA_DIR "/motion/washout.yaml", HARBOUR_DATA_DIR "/machines/hovercraft.yaml"),
      DataError);
}

}  // namespace
}  // namespace harbour::io
