#include "harbour/io/BulkFiles.h"

#include <gtest/gtest.h>

#include "harbour/core/Units.h"
#include "scenes/DataErrors.h"

namespace harbour::io {
namespace {

const std::string kMaterials = HARBOUR_DATA_DIR "/materials.yaml";

const char* kGoodMaterials = R"(materials:
  - name: coal
    bulk_density_kg_m3: 960
    angle_of_repose_deg: 35
    flow_friction_deg: 28
)";

const char* kScenario = R"(bulk:
  material: coal
  grids:
    - name: yard
      cells_x: 10
      cells_y: 10
      cell_size_m: 0.1
  heaps:
    - grid: yard
      x_m: 0.5
      y_m: 0.5
      volume_m3: 1
  grab:
    width_m: 2
    max_opening_m: 3
    max_depth_m: 1
    sinking_speed_mps: 0.2
    spill_speed_mps: 2
    capacity_m3: 10
    closing_time_s: 5
)";

using scenes::expect_data_error;

TEST(BulkFiles, ShippedMaterialsLoadWithPublishedValues) {
  const auto materials = load_materials(kMaterials);
  ASSERT_EQ(materials.size(), 7u);
  EXPECT_EQ(materials[0].name, "coal");
  EXPECT_EQ(materials[0].bulk_density_kg_m3, 960.0);
  EXPECT_DOUBLE_EQ(materials[0].angle_of_repose_rad, core::deg_to_rad(35.0));
}

TEST(BulkFiles, ShippedDemoScenarioLoads) {
  const auto s = load_bulk_scenario(HARBOUR_DATA_DIR "/scenarios/bulk_demo.yaml", load_materials(kMaterials));
  EXPECT_EQ(s.material.name, "coal");
  EXPECT_EQ(s.grids.size(), 2u);
}

TEST(BulkFiles, BadMaterialsNameLineAndField) {
  const auto load = [](const YamlFile& f) { load_materials(f); };
  expect_data_error(kGoodMaterials, "angle_of_repose_deg: 35", "angle_of_repose_deg: 90", load, 4,
                    "materials[0].angle_of_repose_deg");
  expect_data_error(kGoodMaterials, "bulk_density_kg_m3: 960", "bulk_density_kg_m3: heavy", load, 3,
                    "materials[0].bulk_density_kg_m3");
  expect_data_error(kGoodMaterials, "bulk_density_kg_m3: 960", "bulk_density_kg_m3: -960", load, 3,
                    "materials[0].bulk_density_kg_m3");
  expect_data_error(kGoodMaterials, "    flow_friction_deg: 28\n", "", load, 2,
                    "materials[0].flow_friction_deg");
  expect_data_error(kGoodMaterials, "flow_friction_deg: 28", "flow_friction_deg: 36", load, 5,
                    "materials[0].flow_friction_deg");  // steeper than the repose angle
}

TEST(BulkFiles, BadScenarioNamesLineAndField) {
  const auto materials = load_materials(YamlFile::parse(kGoodMaterials, "m.yaml"));
  const auto load = [&](const YamlFile& f) { load_bulk_scenario(f, materials); };
  expect_data_error(kScenario, "material: coal", "material: unobtainium", load, 2, "bulk.material");
  expect_data_error(kScenario, "cell_size_m: 0.1", "cell_size_m: -0.1", load, 7, "bulk.grids[0].cell_size_m");
  expect_data_error(kScenario, "cells_x: 10", "cells_x: 10.5", load, 5, "bulk.grids[0].cells_x");
  expect_data_error(kScenario, "- grid: yard", "- grid: hold", load, 9, "bulk.heaps[0].grid");
  expect_data_error(kScenario, "x_m: 0.5", "x_m: 5", load, 10, "bulk.heaps[0].x_m");  // off the 1 m grid
  expect_data_error(kScenario, "capacity_m3: 10", "capacity_m3: [10]", load, 19, "bulk.grab.capacity_m3");
  // a grid at 1.8e308 m never settled; a typo was read as nothing
  expect_data_error(kScenario, "cell_size_m: 0.1", "cell_size_m: 0.1\n      origin_x_m: 1.79e308", load, 8,
                    "bulk.grids[0].origin_x_m", "is outside [-2000, 2000]");
  expect_data_error(kScenario, "capacity_m3: 10", "capacity_m3: 10\n    capacity: 20", load, 20,
                    "bulk.grab.capacity", "unknown key 'capacity'");
}

TEST(BulkFiles, AFailedLoadLeavesTheCallersDataUntouched) {
  auto materials = load_materials(kMaterials);
  const auto before = materials.size();
  try {
    materials = load_materials(YamlFile::parse("materials:\n  - name: x\n", "bad.yaml"));
  } catch (const DataError&) {
  }
  EXPECT_EQ(materials.size(), before);
}

}  // namespace
}  // namespace harbour::io
