#include "harbour/io/MachineFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/machines/mhc/Files.h"
#include "harbour/machines/sts/Files.h"
#include "harbour/machines/tractor/Files.h"

#include <gtest/gtest.h>

#include <numbers>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "scenes/DataErrors.h"
#include "scenes/MachineControls.h"

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

// The controls a device mapping binds (`harboursim devices --bind --machine FILE`), read from any machine
// file without its machine's loader: the same table its loader gives, for every shipped machine.
TEST(MachineFiles, AnyMachineFilesControlsReadAsItsOwnLoaderReadsThem) {
  const std::map<std::string, scene::ControlTable> loaded = test::shipped_machine_controls();
  ASSERT_EQ(loaded.size(), sim::machine_types().size());
  for (const auto& [kind, table] : loaded) {
    const std::string file = HARBOUR_DATA_DIR "/machines/" + kind + ".yaml";
    EXPECT_EQ(machine_file_controls(file), table) << file;
    EXPECT_GT(table.size(), 3) << file;
  }
  // a kind no machine folder registers is named at its line, with the kinds there are
  std::string text = shipped_sts();
  text.replace(text.find("kind: sts"), 9, "kind: crane");
  const std::string bad = (std::filesystem::temp_directory_path() / "harbour_bad_machine.yaml").string();
  std::ofstream(bad) << text;
  try {
    machine_file_controls(bad);
    FAIL() << "a crane of no registered kind was read";
  } catch (const DataError& e) {
    EXPECT_EQ(e.line(), scenes::line_of(text, "kind: crane"));
    EXPECT_EQ(e.field(), "machine.kind");
    EXPECT_NE(std::string(e.what()).find("straddle_carrier"), std::string::npos) << e.what();
  }
  std::filesystem::remove(bad);
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

// The machine's reader passes over its looks (the image generator reads them) and refuses a key beside them
// that nothing reads.
TEST(MachineFiles, AMachinesReaderLeavesItsLooksToTheImageGenerator) {
  ASSERT_NE(shipped_sts().find("\nlooks:\n"), std::string::npos);
  expect_error("\nlooks:\n", "\nlookz:\n", "lookz", "unknown key 'lookz'", 1);
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
  // a drive too weak to give what it moves its acceleration: the crane would never get going
  expect_error(
      "max_force_n: 1.2e5, brake_force_n: 2.4e5", "max_force_n: 1e-300, brake_force_n: 2.4e5",
      "machine.trolley.drive.max_force_n",
      "cannot give the trolley (3e+04 kg) its acceleration of 0.6 m/s^2: it needs at least 1.8e+04 N");
  expect_error("max_force_n: 4.0e5, brake_force_n: 8.0e5", "max_force_n: 1.0e5, brake_force_n: 8.0e5",
               "machine.gantry.drive.max_force_n", "it needs at least 1.8e+05 N");
  expect_error("    rail_height_m: 49.0", "    rail_height_m: 49.0\n    rail_hieght_m: 49.0",
               "machine.trolley.rail_hieght_m", "unknown key 'rail_hieght_m'", 1);
  expect_error("    initial_size: 40ft", "    initial_size: 40ft\n    initial_size: 20ft",
               "machine.spreader.initial_size", "duplicate key", 1);
}

void expect_mhc_error(const std::string& from, const std::string& to, const std::string& field,
                      const std::string& says, int lines_below = 0) {
  const std::string text = scenes::read_text(HARBOUR_DATA_DIR "/machines/mhc.yaml");
  scenes::expect_data_error(
      text, from, to, [](const YamlFile& f) { load_mhc(f, HARBOUR_DATA_DIR "/machines"); },
      scenes::line_of(text, from) + lines_below, field, says);
}

TEST(MachineFiles, ShippedMhcLoadsWithItsReevings) {
  const sim::MhcSettings m = load_mhc(HARBOUR_DATA_DIR "/machines/mhc.yaml");
  EXPECT_EQ(m.luffing.ropes.size(), 1u);
  EXPECT_EQ(m.hoist.ropes.size(), 4u);
  EXPECT_NEAR(m.boom_min_angle_rad, 15.0 * std::numbers::pi / 180.0, 1e-12);
  ASSERT_EQ(m.capacity_chart.size(), 3u);
  EXPECT_EQ(m.capacity_chart[2].capacity_t, 40.0);
  EXPECT_EQ(m.controls.find("grab"), 3);
  EXPECT_EQ(m.controls.find("sling"), 4);
  ASSERT_TRUE(m.hook);
  EXPECT_EQ(m.hook->hoist.ropes.size(), 4u);
  EXPECT_EQ(m.hook->block_mass_kg, 3500.0);
  ASSERT_EQ(m.hook->capacity_chart.size(), 3u);
  EXPECT_EQ(m.hook->capacity_chart[0].capacity_t, 63.0);
  EXPECT_EQ(machine_file_kind(HARBOUR_DATA_DIR "/machines/mhc.yaml"), "mhc");
}

TEST(MachineFiles, BadMhcFilesNameTheField) {
  expect_mhc_error("kind: mhc", "kind: sts", "machine.kind", "MHC file");
  expect_mhc_error("luffing_reeving: ../reeving/boom_luffing.yaml",
                   "luffing_reeving: ../reeving/mhc_grab.yaml", "machine.boom.luffing_reeving",
                   "bodies must be [house, boom]");
  expect_mhc_error("hoist_reeving: ../reeving/mhc_grab.yaml", "hoist_reeving: ../reeving/boom_luffing.yaml",
                   "machine.grab.hoist_reeving", "bodies must be");
  expect_mhc_error("chart: [[12.0, 64.0], [30.0, 64.0], [48.0, 40.0]]",
                   "chart: [[12.0, 64.0], [48.0, 64.0], [30.0, 40.0]]",
                   "machine.load_moment_limiter.chart[2]", "radii must increase");
  expect_mhc_error("chart: [[12.0, 64.0], [30.0, 64.0], [48.0, 40.0]]", "chart: [[12.0, 64.0]]",
                   "machine.load_moment_limiter.chart", "at least two");
  expect_mhc_error("open_gap_m: 3.4", "open_gap_m: 1.65", "machine.grab.open_gap_m", "shells' travel");
  expect_mhc_error("max_angle_deg: 80", "max_angle_deg: 16", "machine.boom.max_angle_deg", "must exceed");
  expect_mhc_error("hoist_limits_m: [-25.0, 40.0]", "hoist_limits_m: [40.0, -25.0]",
                   "machine.grab.hoist_limits_m", "above lower");
  expect_mhc_error("    - {label: grab, kind: axis,", "    - {label: grip, kind: axis,", "machine.controls",
                   "'grab'", -3);  // at the controls' list
  expect_mhc_error("hoist_reeving: ../reeving/mhc_hook.yaml", "hoist_reeving: ../reeving/mhc_grab.yaml",
                   "machine.hook.hoist_reeving", "bodies must be [house, boom, hook]");
  expect_mhc_error("chart: [[12.0, 63.0], [25.0, 50.0], [48.0, 22.0]]", "chart: [[12.0, 63.0]]",
                   "machine.hook.chart", "at least two");
  expect_mhc_error("slinger_reach_m: 1.0", "slinger_reach_m: 50", "machine.hook.slinger_reach_m", "outside");
  expect_mhc_error("    - {label: sling, kind: button,", "    - {label: slings, kind: button,",
                   "machine.controls", "'sling' button", -4);  // at the controls' list
  expect_mhc_error("    mass_kg: 40000", "    mass_kg: 40000\n    mass_kg_typo: 1",
                   "machine.boom.mass_kg_typo", "mass_kg", 1);
}

}  // namespace
}  // namespace harbour::io

namespace harbour::io {
namespace {

void expect_tractor_error(const std::string& from, const std::string& to, const std::string& field,
                          const std::string& says) {
  const std::string text = scenes::read_text(HARBOUR_DATA_DIR "/machines/tractor.yaml");
  scenes::expect_data_error(
      text, from, to, [](const YamlFile& f) { load_tractor(f); }, scenes::line_of(text, from), field, says);
}

TEST(MachineFiles, ShippedTractorLoadsAndBadOnesNameTheField) {
  const sim::TractorSettings t = load_tractor(HARBOUR_DATA_DIR "/machines/tractor.yaml");
  ASSERT_EQ(t.chassis.axles.size(), 2u);
  EXPECT_NEAR(t.chassis.axles[0].x_m - t.chassis.axles[1].x_m, 2.95, 1e-12);  // published wheelbase
  EXPECT_EQ(t.chassis.drivetrain.torque_curve[1].second, 705.0);              // published peak torque
  EXPECT_EQ(machine_file_kind(HARBOUR_DATA_DIR "/machines/tractor.yaml"), "tractor");
  expect_tractor_error("kind: tractor", "kind: mhc", "machine.kind", "tractor file");
  expect_tractor_error("steered: true, driven: false", "steered: false, driven: false", "machine.axles",
                       "steered and a driven");
  expect_tractor_error("[2200, 560]]", "[1200, 560]]", "machine.drivetrain.torque_curve[2]", "must increase");
  expect_tractor_error("friction: 0.8", "friction: 7", "machine.tyre.friction", "outside");
}

}  // namespace
}  // namespace harbour::io
