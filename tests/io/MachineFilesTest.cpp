#include "harbour/io/MachineFiles.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "scenes/DataErrors.h"

namespace harbour::io {
namespace {

std::string shipped_sts() {
  return scenes::read_text(HARBOUR_DATA_DIR "/machines/sts.yaml");
}

void expect_error(const std::string& from, const std::string& to, const std::string& field,
                  const std::string& says) {
  const std::string text = shipped_sts();
  scenes::expect_data_error(
      text, from, to, [](const YamlFile& f) { load_sts_crane(f, HARBOUR_DATA_DIR "/machines"); },
      scenes::line_of(text, from), field, says);
}

TEST(MachineFiles, ShippedStsLoadsWithItsHoist) {
  const sim::StsCraneSettings s = load_sts_crane(HARBOUR_DATA_DIR "/machines/sts.yaml");
  EXPECT_EQ(s.trolley_drive.max_speed_mps, 4.0);
  EXPECT_EQ(s.hoist.ropes.size(), 4u);
  EXPECT_DOUBLE_EQ(s.spreader_half_extents_m.y, 12.192 / 2);  // along the quay
}

TEST(MachineFiles, BadStsFilesNameTheField) {
  expect_error("hoist_reeving: ../reeving/sts_hoist.yaml", "hoist_reeving: ../reeving/nowhere.yaml",
               "machine.hoist_reeving", "no such file");
  expect_error("hoist_reeving: ../reeving/sts_hoist.yaml", "hoist_reeving: ../reeving/rtg_hoist.yaml",
               "machine.hoist_reeving", "[gantry, trolley, headblock]");
  expect_error("mass_kg: 30000", "mass_kg: -30000", "machine.trolley.mass_kg", "outside");
  expect_error("length_m: 12.192", "length_m: long", "machine.spreader.length_m", "not a number");
}

}  // namespace
}  // namespace harbour::io
