#include "harbour/io/ReevingFiles.h"

#include <gtest/gtest.h>

#include "scenes/DataErrors.h"

#include <algorithm>
#include <string>

namespace harbour::io {
namespace {

const char* kSmall = R"(reeving:
  name: small
  max_substeps: 8
  bodies: [block]
  rope_types:
    - {name: wire, diameter_m: 0.028, mass_per_m_kg: 2.7, axial_stiffness_n: 3.1e7, min_breaking_force_n: 461000}
  elements:
    - {name: drum, kind: drum, body: world, at_m: [0, 0, 10], radius_m: 0.5, inertia_kg_m2: 500,
       max_rope_speed_mps: 1, max_rope_acceleration_mps2: 0.5, max_torque_n_m: 1e5, brake_torque_n_m: 2e5,
       stored_rope_m: 100}
    - {name: sheave, kind: sheave, body: block, at_m: [0, 0, 0], radius_m: 0.3, inertia_kg_m2: 2}
    - {name: dead_end, kind: anchor, body: world, at_m: [1, 0, 10]}
  ropes:
    - {name: hoist, type: wire, path: [drum, sheave, dead_end]}
)";

// one edit to the small reeving above, and the error it must give
void expect_error(const std::string& from, const std::string& to, int line, const std::string& field,
                  const std::string& says) {
  scenes::expect_data_error(
      kSmall, from, to, [](const YamlFile& f) { load_reeving(f); }, line, field, says);
}

TEST(ReevingFiles, ShippedReevingsLoad) {
  for (const char* name : {"sts_hoist", "rtg_hoist", "mhc_grab", "boom_luffing"}) {
    const ReevingFile f = load_reeving(std::string(HARBOUR_DATA_DIR "/reeving/") + name + ".yaml");
    EXPECT_EQ(f.reeving.name, name);
    EXPECT_FALSE(f.reeving.ropes.empty());
  }
  const ReevingFile sts = load_reeving(HARBOUR_DATA_DIR "/reeving/sts_hoist.yaml");
  EXPECT_EQ(sts.reeving.ropes.size(), 4u);
  EXPECT_EQ(sts.bodies, (std::vector<std::string>{"gantry", "trolley", "headblock"}));
}

TEST(ReevingFiles, BadReevingsNameFileLineAndField) {
  expect_error("path: [drum, sheave, dead_end]", "path: [drum, pulley, dead_end]", 14,
               "reeving.ropes[0].path[1]", "unknown element 'pulley'");
  expect_error("path: [drum, sheave, dead_end]", "path: [sheave, dead_end]", 14, "reeving.ropes[0].path[0]",
               "must start at a drum");
  expect_error("diameter_m: 0.028", "diameter_m: -0.028", 6, "reeving.rope_types[0].diameter_m", "outside");
  expect_error("body: block", "body: hook", 11, "reeving.elements[1].body", "unknown body 'hook'");
  expect_error("radius_m: 0.3", "radius_m: x", 11, "reeving.elements[1].radius_m", "not a number");
  expect_error("type: wire,", "type: rope,", 14, "reeving.ropes[0].type", "unknown rope type");
}

}  // namespace
}  // namespace harbour::io

namespace harbour::io {
namespace {

TEST(ReevingFiles, StructureTheWaveModelCannotCarryIsRefused) {
  // a rope from the drum to itself, a sheave passed twice
  expect_error("path: [drum, sheave, dead_end]", "path: [drum, sheave, drum]", 14, "reeving.ropes[0].path[2]",
               "rope 'hoist' meets 'drum' twice");
  // a rope stiffer than a steel bar of its diameter, a sheave far beyond its body
  expect_error("axial_stiffness_n: 3.1e7", "axial_stiffness_n: 1e12", 6,
               "reeving.rope_types[0].axial_stiffness_n", "more than a steel bar of 28 mm gives");
  // ... and ropes no rope could be: softer, lighter or weaker than any fibre rope of its diameter (a rope of
  // EA 1 N never lifted; 1e-9 kg/m passed an exercise; 1e-300 diverged)
  for (const char* soft : {"axial_stiffness_n: 1", "axial_stiffness_n: 1e-300"})
    expect_error("axial_stiffness_n: 3.1e7", soft, 6, "reeving.rope_types[0].axial_stiffness_n",
                 "no 28 mm rope is softer than that");
  expect_error("mass_per_m_kg: 2.7", "mass_per_m_kg: 1e-9", 6, "reeving.rope_types[0].mass_per_m_kg",
               "no 28 mm rope is lighter than that");
  expect_error("at_m: [0, 0, 0]", "at_m: [1e300, 0, 0]", 11, "reeving.elements[1].at_m[0]",
               "is outside [-500, 500]");
  expect_error("  max_substeps: 8", "  max_substeps: 8\n  max_substep: 9", 4, "reeving.max_substep",
               "unknown key 'max_substep'");
}

}  // namespace
}  // namespace harbour::io
