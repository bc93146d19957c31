#include "harbour/io/MachineFiles.h"

#include <gtest/gtest.h>

#include <numbers>

#include <fstream>
#include <sstream>

#include "scenes/DataErrors.h"

namespace harbour::io {
namespace {

std::string shipped_sts() {
  return scenes::read_text(HARBOUR_DATA_DIR "/machines/sts.yaml");
}

void expect_error(const std::string& from, const std::string& to, const std::string& field,
                  const std::string& says, int lines_below = 0) {
  const std::string text = shipped_sts();
  scenes::expect_data_error(
      text, from, to, [](const YamlFile& f) { load_sts_crane(f, HARBOUR_DATA_DIR "/machines"); },
      scenes::line_of(text, from) + lines_below, field, says);
}

TEST(MachineFiles, ShippedStsLoadsWithItsHoist) {
  const sim::StsCraneSettings s = load_sts_crane(HARBOUR_DATA_DIR "/machines/sts.yaml");
  EXPECT_EQ(s.trolley_drive.max_speed_mps, 4.0);
  EXPECT_EQ(s.hoist.ropes.size(), 4u);
  EXPECT_DOUBLE_EQ(s.spreader.length_m[1], 12.192);
  EXPECT_DOUBLE_EQ(s.spreader.pin_span_m[0], 5.853);
  EXPECT_EQ(s.spreader.initial_size, sim::SpreaderSize::k40ft);
  EXPECT_NEAR(s.boom.drive.max_position_m, 80 * std::numbers::pi / 180, 1e-12);
  EXPECT_NEAR(s.boom.drive.max_speed_mps * 300, s.boom.drive.max_position_m, 1e-12);
}

TEST(MachineFiles, BadStsFilesNameTheField) {
  expect_error("hoist_reeving: ../reeving/sts_hoist.yaml", "hoist_reeving: ../reeving/nowhere.yaml",
               "machine.hoist_reeving", "no such file");
  expect_error("hoist_reeving: ../reeving/sts_hoist.yaml", "hoist_reeving: ../reeving/rtg_hoist.yaml",
               "machine.hoist_reeving", "[gantry, trolley, headblock]");
  expect_error("mass_kg: 30000", "mass_kg: -30000", "machine.trolley.mass_kg", "outside");
  expect_error("length_m: 12.192", "length_m: long", "machine.spreader.settings.40ft.length_m",
               "not a number");
  expect_error("length_m: 12.192", "length_m: 6.0", "machine.spreader.settings.40ft.length_m", "outside");
  expect_error("twistlock_span_m: 5.853", "twistlock_span_m: 7",
               "machine.spreader.settings.20ft.twistlock_span_m", "outside");
  expect_error("initial_size: 40ft", "initial_size: 30ft", "machine.spreader.initial_size", "unknown size");
  expect_error("trolley_park_x_m: 10.0", "trolley_park_x_m: -40", "machine.boom.trolley_park_x_m",
               "landside");
}

}  // namespace
}  // namespace harbour::io

namespace harbour::io {
namespace {

TEST(MachineFiles, UnphysicalValuesAndTyposAreRefused) {
  expect_error("    mass_kg: 15000", "    mass_kg: 1", "machine.spreader.mass_kg",
               "1 is outside [1000, 50000]");
  expect_error("    mass_kg: 30000", "    mass_kg: 1e-300", "machine.trolley.mass_kg",
               "is outside [5000, 500000]");
  expect_error("    rail_height_m: 49.0", "    rail_height_m: 49.0\n    rail_hieght_m: 49.0",
               "machine.trolley.rail_hieght_m", "unknown key 'rail_hieght_m'", 1);
  expect_error("    initial_size: 40ft", "    initial_size: 40ft\n    initial_size: 20ft",
               "machine.spreader.initial_size", "duplicate key", 1);
}

}  // namespace
}  // namespace harbour::io
