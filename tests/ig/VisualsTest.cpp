// The look files' reader on its own: what a look is made of, and a bad look named by file, line and field.
#include "harbour/ig/Visuals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>

#include <unistd.h>

#include "harbour/io/DataError.h"
#include "harbour/machines/MachineRegistry.h"

namespace harbour::ig {
namespace {

std::string written(const std::string& name, const std::string& text) {
  // a folder of this process's own: ctest runs this file's tests as processes side by side
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("harbour_visuals_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  const std::string path = (folder / name).string();
  std::ofstream(path) << text;
  return path;
}

TEST(Visuals, ALookIsItsPartsAndLiveries) {
  const std::map<std::string, Visual> looks = load_visuals(written("good.yaml", R"(visuals:
  - key: box
    liveries: [[0.8, 0.1, 0.1], [0.1, 0.1, 0.8]]
    parts:
      - {size: entity, at: [0, 0, 0], color: livery}
      - {shape: lattice, size: [2, 2, 30], at: [1, 2, 3], bay_m: 2.5, member_m: 0.3, color: [0.8, 0.25, 0.1]}
      - {shape: container, size: entity, at: [0, 0, 0], color: livery}
      - {shape: tyre, size: [1.6, 0.6, 1.6], at: [0, 1.3, -0.6], color: [0.08, 0.08, 0.08], rim_color: [0.9, 0.8, 0.1]}
      - {shape: shell, size: [1.5, 2.8, 1.6], hinge_m: 2.3, at: [0, 0, 1.5], yaw_deg: 180, color: [0.9, 0.7, 0.05],
         turns: {with: grab_opening, axis: [0, -0.5, 0], degrees: 90, law: arcsine}}
)"));
  ASSERT_EQ(looks.count("box"), 1u);
  const Visual& box = looks.at("box");
  ASSERT_EQ(box.parts.size(), 5u);
  EXPECT_FALSE(box.parts[0].size_m) << "the entity's own size";
  EXPECT_TRUE(box.parts[0].livery);
  EXPECT_EQ(box.liveries.size(), 2u);
  EXPECT_EQ(box.parts[1].shape, VisualPart::Shape::kLattice);
  EXPECT_EQ(box.parts[1].bay_m, 2.5);
  EXPECT_EQ(box.parts[1].member_m, 0.3);
  EXPECT_EQ(box.parts[1].centre_m.z, 3.0);
  EXPECT_EQ(box.parts[1].size_m->z, 30.0);
  EXPECT_EQ(box.parts[2].shape, VisualPart::Shape::kContainer);
  EXPECT_TRUE(box.parts[2].livery);
  EXPECT_EQ(box.parts[3].shape, VisualPart::Shape::kTyre);
  EXPECT_EQ(box.parts[3].rim_color.y, 0.8);
  const VisualPart& shell = box.parts[4];
  EXPECT_EQ(shell.shape, VisualPart::Shape::kShell);
  EXPECT_EQ(shell.hinge_m, 2.3);
  EXPECT_NEAR(shell.yaw_rad, 3.14159265, 1e-6);
  ASSERT_TRUE(shell.turn);
  EXPECT_EQ(shell.turn->indicator, "grab_opening");
  EXPECT_EQ(shell.turn->axis.y, -1.0) << "a unit axis";
  EXPECT_NEAR(shell.turn->max_rad, 1.57079633, 1e-6);
  EXPECT_TRUE(shell.turn->arcsine);
}

void expect_refused(const std::string& text, int line, const std::string& field, const std::string& says) {
  const std::string path = written("bad.yaml", text);
  try {
    load_visuals(path);
    FAIL() << "accepted";
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(Visuals, ABadLookIsNamedByFileLineAndField) {
  expect_refused("visuals:\n  - key: a\n    parts: [{size: entity, at: [0, 0, 0], color: livery}]\n", 3,
                 "visuals[0].parts[0].color", "a livery colour needs the look's liveries");
  expect_refused("visuals:\n  - key: a\n    parts: []\n  - key: a\n    parts: []\n", 4, "visuals[1].key",
                 "'a' is declared twice");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: sphere, size: [1, 1, 1], at: [0, 0, 0]}\n", 4,
      "visuals[0].parts[0].shape", "not a shape");
  expect_refused("visuals:\n  - key: a\n    parts:\n      - {size: [1, 0, 1], at: [0, 0, 0]}\n", 4,
                 "visuals[0].parts[0].size", "every side must be positive");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: lattice, size: [1, 1, 9], at: [0, 0, 0], color: [0, "
      "0, "
      "0], solid: true}\n",
      4, "visuals[0].parts[0].solid", "only a fixed box with its size written out is solid");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {size: entity, at: [0, 0, 0], color: [0, 0, 0], solid: "
      "true}\n",
      4, "visuals[0].parts[0].solid", "only a fixed box with its size written out is solid");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {size: [1, 1, 1], at: [0, 0, 0], color: [-0.5, 0, 0]}\n", 4,
      "visuals[0].parts[0].color", "colour components are 0-1");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {size: [1, 1, 1], at: [0, 0, 0], color: [2, 0, 0]}\n", 4,
      "visuals[0].parts[0].color", "colour components are 0-1");
  expect_refused("visuals:\n  - key: a\n    parts:\n      - {shape: mesh, file: none.obj, at: [0, 0, 0]}\n",
                 4, "visuals[0].parts[0].file", "no such file");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: tyre, size: [1.6, 0.6, 1.5], at: [0, 0, 0], "
      "color: [0, 0, 0]}\n",
      4, "visuals[0].parts[0].size", "two equal sides");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: tyre, size: entity, at: [0, 0, 0], color: [0, 0, "
      "0]}\n",
      4, "visuals[0].parts[0].size", "written out");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: tyre, size: [1, 0.4, 1], at: [0, 0, 0], color: [0, "
      "0, 0], "
      "rim_color: [1, 2, 0]}\n",
      4, "visuals[0].parts[0].rim_color", "colour components are 0-1");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: shell, size: [1.5, 2.8, 1.6], at: [0, 0, 0], "
      "color: [1, 1, 0],\n         turns: {with: grab_opening, axis: [0, 0, 0], degrees: 90}}\n",
      5, "visuals[0].parts[0].turns.axis", "a direction, not zero");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: shell, size: [1.5, 2.8, 1.6], at: [0, 0, 0], "
      "color: [1, 1, 0],\n         turns: {with: grab_opening, axis: [0, 1, 0], degrees: 90, law: cubic}}\n",
      5, "visuals[0].parts[0].turns.law", "not a law");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n"
      "      - {shape: shell, size: [1.5, 2.8, 1.6], hinge_m: 1.0, at: [0, 0, 0], color: [1, 1, 0]}\n",
      4, "visuals[0].parts[0].hinge_m", "");
}

TEST(Visuals, TheShippedLooksLoad) {
  const Looks looks = load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
  EXPECT_GT(looks.visuals.size(), 20u);
  EXPECT_FALSE(looks.hud.empty());
  EXPECT_FALSE(looks.scenery.empty());
  // each machine's looks come from its own file: none of the harbour's file names a machine's entity
  const Looks harbour = load_looks(HARBOUR_DATA_DIR "/visuals/harbour.yaml");
  const std::map<std::string_view, std::string> main_part = {{"sts", "sts.gantry"},
                                                             {"rtg", "rtg.frame"},
                                                             {"mhc", "mhc.boom"},
                                                             {"reach_stacker", "reach_stacker.chassis"},
                                                             {"tractor", "tractor.chassis"},
                                                             {"straddle_carrier", "straddle_carrier.portal"}};
  for (const std::string_view kind : sim::machine_kinds()) {
    EXPECT_TRUE(main_part.count(kind) && looks.visuals.count(main_part.at(kind))) << kind;
    for (const auto& [key, visual] : harbour.visuals)
      EXPECT_NE(key.rfind(std::string(kind) + ".", 0), 0u) << key << " is the " << kind << "'s";
  }
}

// A machine file's looks beside the harbour's: its HUD lines first on it and in place of the harbour's for
// the same indicator; what is not its own (a look, a lamp or a camera on another's entity) refused by field.
TEST(Visuals, AMachineFilesLooksAreItsOwn) {
  const std::string harbour = written("harbour.yaml", R"(visuals:
  - key: box
    parts: [{size: entity, at: [0, 0, 0], color: [0.5, 0.5, 0.5]}]
hud:
  - {indicator: speed_kmh, label: speed, unit: km/h, decimals: 0}
  - {indicator: horn, label: HORN, lamp: true}
)");
  const std::string machine_head = "machine:\n  kind: tractor\n  mass_kg: 1\nlooks:\n";
  const std::string good = written("tractor.yaml", machine_head + R"(  visuals:
    - key: tractor.chassis
      parts: [{size: entity, at: [0, 0, 0], color: [0.9, 0.5, 0.1]}]
  floodlights:
    - {entity: tractor.chassis, at: [1, 0, 2], color: [1, 1, 1], range_m: 25}
  cameras:
    - {name: reversing, entity: tractor.chassis, at: [0, 0, 2], look: [-1, 0, 0], fov_vertical_deg: 70}
  insets:
    - {camera: reversing, rect: [0.4, 0.03, 0.2, 0.22]}
  hud:
    - {indicator: gear, label: gear, decimals: 0}
    - {indicator: speed_kmh, label: km/h, decimals: 1}
)");
  const Looks looks = load_looks(harbour, {good});
  EXPECT_EQ(looks.visuals.size(), 2u);
  ASSERT_EQ(looks.floodlights.size(), 1u);
  EXPECT_EQ(looks.floodlights[0].entity, "tractor.chassis");
  ASSERT_EQ(looks.insets.size(), 1u);
  std::vector<std::string> on_tractor, on_crane;
  for (const HudItem& line : looks.hud) {
    if (line.shown_on("tractor")) on_tractor.push_back(line.label);
    if (line.shown_on("sts")) on_crane.push_back(line.label);
  }
  EXPECT_EQ(on_tractor, (std::vector<std::string>{"gear", "km/h", "HORN"}));
  EXPECT_EQ(on_crane, (std::vector<std::string>{"speed", "HORN"}));
  // of two files of one kind the last is read (an exercise's own machine file after the shipped one)
  const std::string other = written("tractor2.yaml", machine_head + R"(  visuals:
    - key: tractor.cab
      parts: [{size: entity, at: [0, 0, 0], color: [0.1, 0.5, 0.9]}]
)");
  const Looks replaced = load_looks(harbour, {good, other});
  EXPECT_EQ(replaced.visuals.count("tractor.chassis"), 0u);
  EXPECT_EQ(replaced.visuals.count("tractor.cab"), 1u);
  EXPECT_TRUE(replaced.floodlights.empty());

  const auto refused = [&](const std::string& looks_text, int line, const std::string& field,
                           const std::string& says) {
    const std::string bad = written("bad_tractor.yaml", machine_head + looks_text);
    try {
      load_looks(harbour, {bad});
      ADD_FAILURE() << "accepted: " << looks_text;
    } catch (const io::DataError& e) {
      EXPECT_EQ(e.file(), bad);
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused("  visuals:\n    - key: box\n      parts: []\n", 6, "looks.visuals[0].key", "'tractor.<part>'");
  refused("  visuals:\n    - key: sts.gantry\n      parts: []\n", 6, "looks.visuals[0].key",
          "not 'sts.gantry'");
  refused("  floodlights:\n    - {entity: sts.trolley, at: [0, 0, 0], color: [1, 1, 1], range_m: 20}\n", 6,
          "looks.floodlights[0].entity", "rides one of its own entities");
  refused("  cameras:\n    - {name: c, entity: box, at: [0, 0, 0], look: [1, 0, 0], fov_vertical_deg: 60}\n",
          6, "looks.cameras[0].entity", "rides one of its own entities");
  refused(
      "  festoons:\n    - {from: {entity: tractor.chassis, at: [0, 0, 0]}, to: {entity: sts.trolley, at: [1, "
      "0, "
      "0]}, carriers: 4, loop_m: 2}\n",
      6, "looks.festoons[0].to.entity", "hangs from its own entities");
  refused(
      "  festoons:\n    - {from: {entity: tractor.chassis, at: [0, 0, 0]}, to: {entity: tractor.cab, at: [1, "
      "0, "
      "0]}, carriers: 0, loop_m: 2}\n",
      6, "looks.festoons[0].carriers", "");
  {
    const std::string hung = written("hung_tractor.yaml", machine_head + R"(  festoons:
    - {from: {entity: tractor.chassis, at: [0, 0, 2]}, to: {entity: tractor.cab, at: [3, 0, 0]}, carriers: 4,
       loop_m: 2, cables: 2}
)");
    const Looks festooned = load_looks(harbour, {hung});
    ASSERT_EQ(festooned.festoons.size(), 1u);
    EXPECT_EQ(festooned.festoons[0].to_entity, "tractor.cab");
    EXPECT_DOUBLE_EQ(festooned.festoons[0].from_m.z, 2.0);
    EXPECT_EQ(festooned.festoons[0].cables, 2);
  }
  refused(
      "  cameras:\n    - {name: c, entity: tractor.cab, at: [0, 0, 0], look: [1, 0, 0], fov_vertical_deg: "
      "60}\n"
      "  insets:\n    - {camera: d, rect: [0, 0, 0.2, 0.2]}\n",
      8, "looks.insets[0].camera", "no camera 'd'");
  refused("  hud:\n    - {indicator: gear, label: gear, machines: [sts]}\n", 6, "looks.hud[0].machines",
          "unknown key");
}

}  // namespace
}  // namespace harbour::ig

namespace harbour::ig {
namespace {

// A telescopic spreader drawn as its parts: its twistlocks where ISO 1161 puts a box's castings at each of
// the sizes it telescopes to (ISO 668 lengths), sliding with the published length; its flippers turning about
// their hinges; the main frame inside the 20 ft length.
TEST(Visuals, ASpreadersTwistlocksSlideToTheCastingsOfEverySize) {
  VisualPart spreader;
  spreader.shape = VisualPart::Shape::kSpreader;
  spreader.telescopes_with = "spreader_length_m";
  spreader.locks_with = "lamp_locked";
  spreader.flippers = {"f1", "f2", "f3", "f4"};
  spreader.centre_m = {0.0, 0.0, 0.0};
  const core::Vec3 box{2.438, 12.192, 1.0};  // drawn for 40 ft
  const std::vector<VisualPart> parts = spreader_parts(spreader, box);
  // ISO 1161 casting centres: 2.259 m across; 5.853, 11.985 and 13.509 m along for 20, 40 and 45 ft boxes
  const struct { double length, span; } sizes[] = {{6.058, 5.853}, {12.192, 11.985}, {13.716, 13.509}};
  int cones = 0, heads = 0, flippers = 0;
  for (const VisualPart& p : parts) {
    if (p.shape == VisualPart::Shape::kCylinder) {  // a twistlock's cone
      ++cones;
      ASSERT_TRUE(p.slide);
      EXPECT_EQ(p.slide->indicator, "spreader_length_m");
      EXPECT_NEAR(std::abs(p.centre_m.x), 2.259 / 2.0, 1e-9);
      for (const auto& size : sizes) {
        const double y = p.centre_m.y + p.slide->along.y * (size.length - p.slide->from);
        // (a 20 ft box's castings sit 1 mm further in from its ends than a 40 or 45 ft box's)
        EXPECT_NEAR(std::abs(y), size.span / 2.0, 1.5e-3) << size.length;
      }
      EXPECT_LT(p.centre_m.z, -0.5);  // under the spreader
    }
    if (p.turn && p.turn->indicator == "lamp_locked") {  // a twistlock's head: a quarter turn about z
      ++heads;
      EXPECT_NEAR(p.turn->max_rad, std::numbers::pi / 2.0, 1e-12);
      EXPECT_EQ(p.turn->axis.z, 1.0);
    }
    if (p.turn && p.turn->indicator.starts_with("f")) {
      ++flippers;
      ASSERT_TRUE(p.turn->pivot_m);
      const core::Vec3 hinge = *p.turn->pivot_m;
      EXPECT_NEAR(std::abs(hinge.y), box.y / 2.0, 1e-9);  // at the corner's end
      EXPECT_GT(std::abs(hinge.x), box.x / 2.0);          // outside its side
      EXPECT_NEAR(hinge.z, -box.z / 2.0, 1e-9);           // on its lower edge
      EXPECT_NEAR(std::abs(p.turn->max_rad), std::numbers::pi, 1e-12);
      // folded up outboard: turning outward over the top (+180 deg about +y at +x, -180 at -x) brings it down
      EXPECT_GT(p.centre_m.x * hinge.x, hinge.x * hinge.x);
      EXPECT_GT(p.turn->max_rad * hinge.x, 0.0);
      ASSERT_TRUE(p.slide);  // and it rides its end
      EXPECT_NEAR(p.slide->along.y * hinge.y, 0.5 * std::abs(hinge.y), 1e-12);
    }
    if (p.shape == VisualPart::Shape::kGirder && p.size_m->y > p.size_m->x) {  // the main frame
      EXPECT_LT(p.size_m->y, 6.058 - 1.0);
    }
  }
  EXPECT_EQ(cones, 4);
  EXPECT_EQ(heads, 4);
  EXPECT_EQ(flippers, 12);  // an end plate, a side plate and an arm a corner
  // corner c's flipper turns with the c-th indicator, in the twistlocks' order: +y -x, -y -x, -y +x, +y +x
  const double signs[4][2] = {{-1, 1}, {-1, -1}, {1, -1}, {1, 1}};
  for (const VisualPart& p : parts)
    if (p.turn && p.turn->indicator.starts_with("f")) {
      const int c = p.turn->indicator[1] - '1';
      EXPECT_GT(p.turn->pivot_m->x * signs[c][0], 0.0) << c;
      EXPECT_GT(p.turn->pivot_m->y * signs[c][1], 0.0) << c;
    }
  // without the indicators nothing moves
  VisualPart still = spreader;
  still.telescopes_with.clear();
  still.locks_with.clear();
  still.flippers.clear();
  for (const VisualPart& p : spreader_parts(still, box))
    EXPECT_FALSE(p.turn || p.slide);
}

TEST(Visuals, ABadSpreaderIsNamedByField) {
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: spreader, size: [2.4, 12, 1], at: [0, 0, 0], "
      "color: [1, 1, 0],\n         flippers: [f1, f2, f3]}\n",
      5, "visuals[0].parts[0].flippers", "four indicators");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: spreader, size: [2.4, 3, 1], at: [0, 0, 0], "
      "color: [1, 1, 0]}\n",
      4, "visuals[0].parts[0].size", "longer (y) than twice its width");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: spreader, size: entity, at: [0, 0, 0], "
      "color: [1, 1, 0],\n         turns: {with: x, axis: [0, 0, 1], degrees: 90}}\n",
      4, "visuals[0].parts[0]", "no turns, slides or yaw of its own");
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {size: [1, 1, 1], at: [0, 0, 0], color: [1, 1, 0],\n"
      "         slides: {with: x}}\n",
      5, "visuals[0].parts[0].slides.along", "");
}

TEST(Visuals, AMachinesJacksJoinItsOwnEntities) {
  const std::string harbour = written("harbour_no_looks.yaml", "visuals: []\n");
  const std::string head = "machine:\n  kind: reach_stacker\n  mass_kg: 1\nlooks:\n  jacks:\n    - ";
  const std::string good =
      written("rs.yaml", head + R"({from: {entity: reach_stacker.chassis, at: [0.3, 0.3, -0.9]},
       to: {entity: reach_stacker.boom, at: [-2.0, 0.3, -0.55]}, barrel_m: 2.4, rod_m: 2.45, diameter_m: 0.3,
       color: [0.7, 0.1, 0.1]}
)");
  const Looks looks = load_looks(harbour, {good});
  ASSERT_EQ(looks.jacks.size(), 1u);
  EXPECT_EQ(looks.jacks[0].from_entity, "reach_stacker.chassis");
  EXPECT_EQ(looks.jacks[0].to_entity, "reach_stacker.boom");
  EXPECT_EQ(looks.jacks[0].to_m.x, -2.0);
  EXPECT_EQ(looks.jacks[0].rod_m, 2.45);
  const auto refused = [&](const std::string& jack, const std::string& field, const std::string& says) {
    try {
      load_looks(harbour, {written("rs_bad.yaml", head + jack + "\n")});
      FAIL() << "accepted " << jack;
    } catch (const io::DataError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused(
      "{from: {entity: sts.trolley, at: [0, 0, 0]}, to: {entity: reach_stacker.boom, at: [0, 0, 0]}, "
      "barrel_m: 2, rod_m: 2, diameter_m: 0.3, color: [1, 0, 0]}",
      "looks.jacks[0].from.entity", "a reach_stacker's jack joins its own entities");
  refused(
      "{from: {entity: reach_stacker.chassis, at: [0, 0, 0]}, to: {entity: reach_stacker.boom, at: [0, 0, "
      "0]}, "
      "barrel_m: 2, rod_m: 3, diameter_m: 0.3, color: [1, 0, 0]}",
      "looks.jacks[0].rod_m", "retracts into its barrel");
  refused(
      "{from: {entity: reach_stacker.chassis, at: [0, 0, 0]}, to: {entity: reach_stacker.boom, at: [0, 0, "
      "0]}, "
      "barrel_m: 2, rod_m: 2, color: [1, 0, 0]}",
      "looks.jacks[0].diameter_m", "missing");
}

// A deckhouse drawn as its parts: a band of windows on every deck above the lowest on its front and both
// sides, the wheelhouse on top at its front, bridge wings 1 m past its sides, the mast on the wheelhouse.
TEST(Visuals, ADeckhouseHasAWindowBandADeckAndItsWheelhouseAtTheFront) {
  VisualPart house;
  house.shape = VisualPart::Shape::kDeckhouse;
  house.centre_m = {0.0, -62.0, 18.5};
  house.color = {0.9, 0.9, 0.9};
  const core::Vec3 size{20.0, 10.0, 14.0};  // five decks of 2.8 m
  const std::vector<VisualPart> parts = deckhouse_parts(house, size);
  const double top = 18.5 + 7.0, front = -62.0 + 5.0;
  int bands = 0, walkways = 0, masts = 0;
  bool wheelhouse = false;
  for (const VisualPart& p : parts) {
    if (p.surface == Surface::kGlass && p.centre_m.z < top) {  // the block's windows
      ++bands;
      const double above_deck = std::fmod(p.centre_m.z - (18.5 - 7.0), kDeckHeight_m);
      EXPECT_NEAR(above_deck, 0.55 * kDeckHeight_m, 1e-9);
      EXPECT_GT(p.centre_m.z, 18.5 - 7.0 + kDeckHeight_m);  // none on the lowest deck
    }
    if (p.shape == VisualPart::Shape::kBox && p.surface == Surface::kPaint && p.size_m->z == 3.0) {
      wheelhouse = true;
      EXPECT_NEAR(p.centre_m.z, top + 1.5, 1e-9);
      EXPECT_NEAR(p.centre_m.y + p.size_m->y / 2.0, front, 1e-9);  // flush with the front
      EXPECT_NEAR(p.size_m->x, 14.0, 1e-9);
    }
    if (p.shape == VisualPart::Shape::kWalkway) {
      ++walkways;
      EXPECT_NEAR(std::abs(p.centre_m.x) + p.size_m->x / 2.0, 11.0, 1e-9);  // 1 m past the side
      EXPECT_NEAR(p.centre_m.z - p.size_m->z / 2.0, top, 1e-9);             // on the wheelhouse's floor
    }
    if (p.shape == VisualPart::Shape::kMember) {
      ++masts;
      EXPECT_NEAR(p.centre_m.z - p.size_m->x / 2.0, top + 3.0, 1e-9);  // on the wheelhouse's roof
    }
  }
  EXPECT_EQ(bands, 4 * 3);  // four decks above the main deck, front and both sides
  EXPECT_TRUE(wheelhouse);
  EXPECT_EQ(walkways, 2);
  EXPECT_EQ(masts, 1);
  expect_refused(
      "visuals:\n  - key: a\n    parts:\n      - {shape: deckhouse, size: [20, 10, 5], at: [0, 0, 0], color: "
      "[1, 1, 1]}\n",
      4, "visuals[0].parts[0].size", "two decks");
}

// A repeated part turning about a point of its own: each copy turns about its own point, a step apart.
TEST(Visuals, ARepeatedPartTurnsAboutItsOwnPivot) {
  const std::map<std::string, Visual> looks = load_visuals(written("pivots.yaml", R"(visuals:
  - key: flaps
    parts:
      - {size: [0.5, 0.1, 0.4], at: [1.25, 0, -0.2], color: [1, 1, 0], repeat: 3, step: [0, 2, 0],
         turns: {with: flap, axis: [0, 1, 0], degrees: 180, about: [1, 0, 0]}}
)"));
  const Visual& flaps = looks.at("flaps");
  ASSERT_EQ(flaps.parts.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(flaps.parts[k].turn && flaps.parts[k].turn->pivot_m);
    EXPECT_EQ(flaps.parts[k].centre_m.y, 2.0 * static_cast<double>(k));
    EXPECT_EQ(flaps.parts[k].turn->pivot_m->y, 2.0 * static_cast<double>(k));
    EXPECT_EQ(flaps.parts[k].turn->pivot_m->x, 1.0);
  }
}

}  // namespace
}  // namespace harbour::ig
