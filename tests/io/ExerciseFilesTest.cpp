#include "harbour/io/ExerciseFiles.h"

#include <gtest/gtest.h>

#include <numbers>
#include <set>
#include <variant>

#include <chrono>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "harbour/io/DataError.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/machines/tractor/TerminalTractor.h"
#include "scenes/DataErrors.h"

namespace harbour::io {
namespace {

std::string shipped() {
  return scenes::read_text(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
}

void expect_error(const std::string& from, const std::string& to, const std::string& field,
                  const std::string& says, int lines_below = 0) {
  const std::string text = shipped();
  scenes::expect_data_error(
      text, from, to, [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
      scenes::line_of(text, from) + lines_below, field, says);
}

TEST(ExerciseFiles, EveryShippedExerciseSaysWhatItIsUnderATitleOfItsOwn) {
  std::set<std::string> titles;
  const std::vector<ExerciseCard> cards = exercise_cards({HARBOUR_DATA_DIR "/exercises"});
  ASSERT_EQ(cards.size(), exercise_names(HARBOUR_DATA_DIR "/exercises").size());
  for (const ExerciseCard& card : cards) {
    EXPECT_EQ(card.error, "") << card.name;
    ASSERT_TRUE(card.about) << card.name << " has no exercise.about";
    EXPECT_TRUE(titles.insert(card.about->title).second)
        << card.name << ": '" << card.about->title << "' twice";
    EXPECT_GE(card.about->objective.size(), 20u) << card.name;
    EXPECT_GT(card.about->expected_min, 0.0) << card.name;
    EXPECT_FALSE(card.machine.empty()) << card.name;
    EXPECT_EQ(load_exercise(std::string(HARBOUR_DATA_DIR "/exercises/") + card.name + ".yaml").about->title,
              card.about->title);
  }
  const ExerciseCard sts = read_exercise_card(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  EXPECT_EQ(sts.machine, "sts");
  EXPECT_EQ(sts.about->difficulty, "beginner");
  // a title is taken whatever the case of its letters, except by the file itself
  EXPECT_NE(why_title_taken({HARBOUR_DATA_DIR "/exercises"}, "first DISCHARGE onto a truck", ""), "");
  EXPECT_EQ(why_title_taken({HARBOUR_DATA_DIR "/exercises"}, "First discharge onto a truck", "sts_discharge"),
            "");
  EXPECT_EQ(why_title_taken({HARBOUR_DATA_DIR "/exercises"}, "Something new", ""), "");
}

TEST(ExerciseFiles, ABadDescriptionNamesItsField) {
  expect_error("difficulty: beginner", "difficulty: easy", "exercise.about.difficulty",
               "beginner, intermediate or advanced");
  expect_error("expected_min: 3", "expected_min: 0", "exercise.about.expected_min", "outside");
  expect_error("    title: First discharge onto a truck\n", "    title: ''\n", "exercise.about.title",
               "empty");
}

TEST(ExerciseFiles, AnMhcExerciseStartsTheCraneWhereItSays) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_free_practice.yaml");
  const auto& mhc = e.scenario.machine.as<sim::MhcSetup>();
  EXPECT_NEAR(mhc.start.boom_rad, 46.0 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_EQ(mhc.start.hanging_z_m, 20.0);
  EXPECT_TRUE(e.moves.empty());
  EXPECT_STREQ(e.scenario.machine.kind(), "mhc");
}

TEST(ExerciseFiles, AnExerciseTheMachineCannotDoNamesTheField) {
  const std::string text = scenes::read_text(HARBOUR_DATA_DIR "/exercises/mhc_free_practice.yaml");
  const auto expect = [&](const std::string& from, const std::string& to, const std::string& field,
                          const std::string& says, int lines_below) {
    scenes::expect_data_error(
        text, from, to, [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
        scenes::line_of(text, from) + lines_below, field, says);
  };
  expect("  quay_edge_x_m: 18.0", "  quay_edge_x_m: 18.0\n  moves:\n    - {container: X, to: truck}",
         "exercise.moves", "crane.tool: hook", 2);
  expect("grab_z_m: 20.0}", "grab_z_m: 20.0, tool: crane}", "exercise.crane.tool", "grab or hook", 0);
  // a missing key is named at the exercise map's first line
  expect("grab_z_m: 20.0}", "hook_z_m: 20.0, tool: hook}", "exercise.cargo", "missing",
         scenes::line_of(text, "  name: mhc_free_practice") - scenes::line_of(text, "grab_z_m: 20.0}"));
  expect("slew_deg: 0,", "gantry_y_m: 0,", "exercise.crane.slew_deg", "missing", 0);
  expect("boom_deg: 46", "boom_deg: 5", "exercise.crane.boom_deg", "outside", 0);
  expect("  quay_edge_x_m: 18.0",
         "  quay_edge_x_m: 18.0\n  events:\n    - {at_s: 1, kind: landed_sensor_fault, corner: 0}",
         "exercise.events[0].kind", "no twistlocks", 2);
}

TEST(ExerciseFiles, AHookExerciseNamesTheFieldItCannotPlace) {
  const std::string text = scenes::read_text(HARBOUR_DATA_DIR "/exercises/mhc_hook_lift.yaml");
  const auto expect = [&](const std::string& from, const std::string& to, const std::string& field,
                          const std::string& says, const std::string& on_line_of = "") {
    scenes::expect_data_error(
        text, from, to, [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
        scenes::line_of(text, on_line_of.empty() ? from : on_line_of), field, says);
  };
  expect("{cargo: TRAFO-1,", "{cargo: TRAFO-2,", "exercise.moves[0].cargo", "no cargo 'TRAFO-2'");
  expect("{cargo: TRAFO-1,", "{container: TRAFO-1,", "exercise.moves[0].cargo", "missing");
  expect("size_m: [5.0, 3.0, 3.5]", "size_m: [5.0, 0.2, 3.5]", "exercise.cargo[0].size_m", "at least 0.5 m");
  expect("mass_kg: 30000", "mass_kg: -3", "exercise.cargo[0].mass_kg", "outside");
  expect("hook_z_m: 14.0, tool: hook", "grab_z_m: 14.0", "exercise.cargo", "crane.tool: hook",
         "    - {id: TRAFO-1");
}

TEST(ExerciseFiles, ATrailerExerciseCouplesItLevelAndNamesTheFieldItCannotPlace) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_mafi_park.yaml");
  const auto& tractor = e.scenario.machine.as<sim::TractorSetup>();
  ASSERT_TRUE(tractor.start.trailer);
  EXPECT_EQ(tractor.start.trailer->id, "mafi_1");
  EXPECT_EQ(tractor.start.trailer->mass_kg, 8500.0 + 30000.0);  // tare and payload
  ASSERT_EQ(e.moves.size(), 1u);
  EXPECT_TRUE(e.moves[0].on_wheels);
  EXPECT_NEAR(*e.moves[0].heading_rad, std::numbers::pi, 1e-12);
  ASSERT_EQ(e.speed_zones.size(), 2u);
  EXPECT_EQ(e.speed_zones[1].limit_kmh, 10.0);
  // its bay painted on the quay: the trailer's footprint and the tolerance around it
  ASSERT_EQ(e.scenario.markings.size(), 1u);
  EXPECT_EQ(e.scenario.markings[0].name, "bay mafi_1");
  EXPECT_NEAR(e.scenario.markings[0].half_length_m, 6.1 + 0.5, 1e-12);
  EXPECT_NEAR(e.scenario.markings[0].half_width_m, 1.3 + 0.5, 1e-12);

  const std::string text = scenes::read_text(HARBOUR_DATA_DIR "/exercises/tractor_mafi_park.yaml");
  const auto expect = [&](const std::string& from, const std::string& to, const std::string& field,
                          const std::string& says, int lines_below = 0) {
    scenes::expect_data_error(
        text, from, to, [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
        scenes::line_of(text, from) + lines_below, field, says);
  };
  expect("{trailer: mafi_1,", "{trailer: mafi_2,", "exercise.moves[0].trailer", "no trailer 'mafi_2'");
  expect("payload_kg: 30000", "payload_kg: 90000", "exercise.vehicle.trailer.payload_kg", "outside");
  expect("file: ../trailers/mafi_40ft.yaml", "file: ../trailers/none.yaml", "exercise.vehicle.trailer.file",
         "no such file");
  expect("heading_deg: 180, heading_tolerance_deg: 3,", "heading_tolerance_deg: 3,",
         "exercise.moves[0].heading_tolerance_deg", "needs a heading_deg");
  expect("min_m: [-80, 10], max_m: [-20, 20]", "min_m: [-80, 10], max_m: [-90, 20]",
         "exercise.speed_zones[1].max_m", "beyond min_m");
  expect("    trailer: {id: mafi_1, file: ../trailers/mafi_40ft.yaml, payload_kg: 30000}\n", "",
         "exercise.moves", "a trailer (exercise.vehicle.trailer)", 2);
}

TEST(ExerciseFiles, ARouteIsReadInOrderAndABadPointIsNamed) {
  const sim::ExerciseSettings e =
      load_exercise(HARBOUR_DATA_DIR "/exercises/reach_stacker_truck_slalom.yaml");
  ASSERT_EQ(e.route_m.size(), 8u);
  EXPECT_EQ(e.route_m[1].x, -121.0);
  EXPECT_EQ(e.route_m[3].y, -47.0);
  const std::string text = scenes::read_text(HARBOUR_DATA_DIR "/exercises/reach_stacker_truck_slalom.yaml");
  const auto expect = [&](const std::string& from, const std::string& to, const std::string& field,
                          const std::string& says) {
    scenes::expect_data_error(
        text, from, to, [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
        scenes::line_of(text, from), field, says);
  };
  expect("[-109.0, -33.0]", "[-109.0]", "exercise.route_m[2]", "is [x, y] in metres");
  expect("[-109.0, -33.0]", "[-120.5, -33.0]", "exercise.route_m[2]", "within a metre");
  expect("[-109.0, -33.0]", "[-109.0, 5000.0]", "exercise.route_m[2]", "off the site");
}

TEST(ExerciseFiles, ARampExerciseLoadsItsRampAndNamesTheFieldItCannotPlace) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/tractor_ramp_mafi.yaml");
  ASSERT_TRUE(e.scenario.ramp);
  EXPECT_EQ(e.scenario.ramp->deck_height_m, 1.8);
  EXPECT_EQ(e.scenario.ramp->tide.amplitude, 0.4);
  EXPECT_EQ(e.scenario.ramp->heave.period_s, 9.0);
  const std::string text = scenes::read_text(HARBOUR_DATA_DIR "/exercises/tractor_ramp_mafi.yaml");
  const auto expect = [&](const std::string& from, const std::string& to, const std::string& field,
                          const std::string& says, int lines_below = 0) {
    scenes::expect_data_error(
        text, from, to, [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
        scenes::line_of(text, from) + lines_below, field, says);
  };
  expect("deck_height_m: 1.8", "deck_height_m: 4.5", "exercise.ramp", "steeper than 1:4", -5);
  expect("length_m: 18", "length_m: -18", "exercise.ramp.length_m", "outside");
  expect("heave: {amplitude_m: 0.08,", "heave: {amplitude_m: 8,", "exercise.ramp.heave.amplitude_m",
         "outside");
  expect("grip: 0.8", "grip: 0", "exercise.ramp.grip", "outside");
  // a crane does not drive up a ramp
  const std::string mhc = scenes::read_text(HARBOUR_DATA_DIR "/exercises/mhc_free_practice.yaml");
  scenes::expect_data_error(
      mhc, "  quay_edge_x_m: 18.0",
      "  quay_edge_x_m: 18.0\n  ramp: {toe_m: [0, 0, 0], heading_deg: 0, length_m: 18, width_m: 8, "
      "deck_length_m: 40, deck_height_m: 1.8}",
      [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
      scenes::line_of(mhc, "  quay_edge_x_m: 18.0") + 1, "exercise.ramp", "only a vehicle");
}

TEST(ExerciseFiles, ATrailerThatWouldNotRideLevelOrStandOnItsLegsIsRefused) {
  const std::string exercise = scenes::read_text(HARBOUR_DATA_DIR "/exercises/tractor_mafi_park.yaml");
  const std::string trailer = scenes::read_text(HARBOUR_DATA_DIR "/trailers/mafi_40ft.yaml");
  const auto error_with = [&](const std::string& from, const std::string& to) {
    const std::filesystem::path folder = std::filesystem::temp_directory_path() / "harbour_trailer_check";
    std::filesystem::create_directories(folder / "exercises");
    std::filesystem::create_directories(folder / "trailers");
    std::filesystem::create_directories(folder / "machines");
    std::filesystem::copy_file(HARBOUR_DATA_DIR "/machines/tractor.yaml", folder / "machines/tractor.yaml",
                               std::filesystem::copy_options::overwrite_existing);
    std::string changed = trailer;
    const auto at = changed.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    changed.replace(at, from.size(), to);
    std::ofstream(folder / "trailers/mafi_40ft.yaml") << changed;
    std::ofstream(folder / "exercises/tractor_mafi_park.yaml") << exercise;
    try {
      load_exercise((folder / "exercises/tractor_mafi_park.yaml").string());
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  EXPECT_EQ(error_with("tare_kg: 8500", "tare_kg: 8500"), "loaded");
  std::string error = error_with("kingpin_m: [5.6, 0.0, 1.0]", "kingpin_m: [5.6, 0.0, 0.5]");
  EXPECT_NE(error.find("exercise.vehicle.trailer.file"), std::string::npos) << error;
  EXPECT_NE(error.find("would not ride level"), std::string::npos) << error;
  error = error_with("foot_z_m: -0.75", "foot_z_m: -0.5");
  EXPECT_NE(error.find("its legs stand 0.35 m clear"), std::string::npos) << error;
  error = error_with("{x_m: -4.5, half_track_m: 0.95,", "{x_m: -4.5, steered: true, half_track_m: 0.95,");
  EXPECT_NE(error.find("trailer.axles[0]"), std::string::npos) << error;
  EXPECT_NE(error.find("neither steer nor drive"), std::string::npos) << error;
}

TEST(ExerciseFiles, ABulkExerciseNamesTheFieldItCannotPlace) {
  const std::string text = scenes::read_text(HARBOUR_DATA_DIR "/exercises/mhc_coal_discharge.yaml");
  const auto expect = [&](const std::string& from, const std::string& to, const std::string& field,
                          const std::string& says, const std::string& on_line_of = "") {
    scenes::expect_data_error(
        text, from, to, [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
        scenes::line_of(text, on_line_of.empty() ? from : on_line_of), field, says);
  };
  expect("vessel_hold: 3,", "vessel_hold: 7,", "exercise.bulk.grids[0].vessel_hold", "no hold 7");
  expect("vessel_hold: 3,", "vessel_hold: 3, cells_x: 10,", "exercise.bulk.grids[0].cells_x", "moves with");
  expect("  deliver: {into: hopper, tonnes: 36}", "  deliver: {into: chute, tonnes: 36}",
         "exercise.deliver.into", "no bulk grid named 'chute'");
  // the hold of a container vessel is no bulk hold
  expect("handysize_bulk.yaml", "feeder_1100teu.yaml", "exercise.bulk.grids[0].vessel_hold", "bulk carrier",
         "vessel_hold: 3,");
}

TEST(ExerciseFiles, TheCoalDischargeLoadsItsHoldOnTheBulkCarrier) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/mhc_coal_discharge.yaml");
  ASSERT_TRUE(e.scenario.vessel && e.scenario.bulk && e.deliver);
  EXPECT_EQ(e.scenario.vessel->vessel.kind, sim::VesselKind::kBulk);
  const bulk::GridPlacement& hold = e.scenario.bulk->grids[0];
  EXPECT_TRUE(hold.on_vessel);
  // side shell to side shell (30 m beam less two 0.4 m shells), between the cross decks (20 m + coamings)
  EXPECT_EQ(hold.settings.cells_x, 146);
  EXPECT_EQ(hold.settings.cells_y, 103);
  EXPECT_NEAR(hold.origin_z_m, 1.6, 1e-12);
  EXPECT_EQ(e.deliver->grid_index, 1);
  EXPECT_EQ(e.deliver->tonnes, 36.0);
  EXPECT_TRUE(e.scenario.containers.empty());  // a bulk carrier's open hatches are no hatch-cover boxes
}

TEST(ExerciseFiles, ShippedDischargeLoads) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  EXPECT_EQ(e.name, "sts_discharge");
  ASSERT_EQ(e.scenario.containers.size(), 3u + 6u);  // and two hatch cover panels on each of three bays
  EXPECT_DOUBLE_EQ(e.scenario.containers[1].half_extents_m.x, 12.192 / 2);  // ISO 668 40 ft
  ASSERT_EQ(e.moves.size(), 1u);
  EXPECT_EQ(e.moves[0].container_id, "TGHU1000012");
  EXPECT_NEAR(e.moves[0].target_m.z, 1.5 + 2.591 / 2, 1e-12);  // on the truck's chassis
  // bay 12, row 01 (first row to starboard of the centreline), tier 82 (first on deck), along the quay
  EXPECT_NEAR(e.scenario.containers[1].pose.position.x, 31.0 + 2.54 / 2, 1e-9);
  EXPECT_NEAR(e.scenario.containers[1].pose.position.y, 0.0, 1e-9);
  EXPECT_NEAR(e.scenario.containers[1].pose.rotation.m[1][0], 1.0, 1e-12);
  EXPECT_EQ(e.scenario.containers[8].id, "HATCH16S");
  EXPECT_EQ(e.scenario.containers[8].kind, sim::ContainerPlacement::Kind::kHatchCover);
  EXPECT_EQ(e.rules.time_limit_s, 180.0);
  EXPECT_EQ(e.rules.points_hard_landing, 5.0);
}

TEST(ExerciseFiles, WeatherAndEventsLoad) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge_gusty.yaml");
  EXPECT_EQ(e.scenario.weather.wind_mean_mps, 10.0);
  EXPECT_NEAR(e.scenario.weather.wind_from_rad, 3.14159265358979, 1e-9);
  ASSERT_EQ(e.scenario.events.size(), 1u);
  EXPECT_EQ(e.scenario.events[0].kind, sim::ScriptedEvent::Kind::kGust);
  EXPECT_EQ(e.scenario.events[0].gust.amplitude_mps, 8.0);
}

// An event timed from the first lift goes to its own list; an event with both clocks, or lift events out of
// order, is refused naming the field.
TEST(ExerciseFiles, EventsTimedFromTheFirstLiftLoadApart) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/sts_hoist_brake_fault.yaml");
  EXPECT_TRUE(e.scenario.events.empty());
  ASSERT_EQ(e.scenario.lift_events.size(), 1u);
  EXPECT_EQ(e.scenario.lift_events[0].kind, sim::ScriptedEvent::Kind::kHoistBrakeFault);
  EXPECT_EQ(e.scenario.lift_events[0].at_s, 8.0);
  const std::string with_events = "  moves:";
  expect_error(with_events, "  events:\n    - {at_s: 3, after_lift_s: 8, kind: hoist_brake_fault}\n  moves:",
               "exercise.events[0].after_lift_s", "not both", 1);
  expect_error(with_events,
               "  events:\n    - {after_lift_s: 8, kind: hoist_brake_fault}\n"
               "    - {at_s: 1, kind: gust, amplitude_mps: 5}\n    - {after_lift_s: 2, kind: "
               "hoist_brake_fault}\n  moves:",
               "exercise.events[2].after_lift_s", "events after the first lift must be in time order", 3);
  // a fault is named as the instructor's command of the same name, spelt either way; an unknown one is
  // refused with the events there are
  std::string hyphens = shipped();
  hyphens.replace(hyphens.find(with_events), with_events.size(),
                  "  events:\n    - {at_s: 1, kind: landed-sensor-fault, corner: 2}\n  moves:");
  const sim::ExerciseSettings spelt =
      load_exercise(YamlFile::parse(hyphens, "hyphens.yaml"), HARBOUR_DATA_DIR "/exercises");
  ASSERT_EQ(spelt.scenario.events.size(), 1u);
  EXPECT_EQ(spelt.scenario.events[0].kind, sim::ScriptedEvent::Kind::kLandedSensorFault);
  EXPECT_EQ(spelt.scenario.events[0].corner, 2);
  expect_error(
      with_events,
      "  events:\n    - {at_s: 1, kind: hoist-brake-faults}\n  moves:", "exercise.events[0].kind",
      "'hoist-brake-faults' is not an event: gust, hoist_brake_fault, landed_sensor_fault, limiter_fault", 1);
  // a fault of a part the machine lacks would do nothing: refused, with the events it has
  expect_error(with_events,
               "  events:\n    - {at_s: 1, kind: limiter_fault}\n  moves:", "exercise.events[0].kind",
               "the sts has no load-moment limiter to fail (its events: gust, hoist_brake_fault, "
               "landed_sensor_fault)",
               1);
}

TEST(ExerciseFiles, EveryShippedExerciseLoadsAndItsMovesAreFeasible) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/exercises")) {
    SCOPED_TRACE(entry.path().string());
    const sim::ExerciseSettings e = load_exercise(entry.path().string());
    ++files;
    EXPECT_EQ(e.name + ".yaml", entry.path().filename().string());
    int to_trucks = 0;
    for (const sim::MoveGoal& m : e.moves)
      to_trucks += m.target_m.x == e.scenario.trucks.lane_x_m && m.target_m.y == e.scenario.trucks.stop_y_m;
    EXPECT_LE(to_trucks, e.scenario.trucks.trucks);  // a truck for every box that goes to one
  }
  EXPECT_GE(files, 4);
}

TEST(ExerciseFiles, TheHoldExerciseLiftsAHatchCoverAndBoxesFromTheCells) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/sts_bay12_hold.yaml");
  ASSERT_EQ(e.moves.size(), 5u);
  EXPECT_EQ(e.moves[2].container_id, "HATCH12S");
  int in_cells = 0;
  for (const sim::ContainerPlacement& c : e.scenario.containers)
    in_cells += c.in_cell;
  EXPECT_EQ(in_cells, 4);  // tiers 02, 04, 06 of row 01 and 02 of row 03
}

TEST(ExerciseFiles, BadExercisesNameTheField) {
  expect_error("{id: TGHU1000012, type: 40ft", "{id: TGHU1000012, type: 53ft", "exercise.containers[1].type",
               "unknown container type '53ft'");
  expect_error("container: TGHU1000012", "container: TGHU1000099", "exercise.moves[0].container",
               "no container 'TGHU1000099'");
  expect_error("slot: [12, 1, 82]", "slot: [12, 9, 82]", "exercise.containers[1].slot", "no row 9");
  expect_error("slot: [12, 3, 82]", "slot: [13, 3, 82]", "exercise.containers[0].slot", "no 40 ft bay 13");
  expect_error("slot: [12, 2, 82]", "slot: [12, 2, 81]", "exercise.containers[2].slot", "tier 81");
  expect_error("{id: TGHU1000014, type: 40ft, gross_mass_kg: 22000, slot: [12, 2, 82]",
               "{id: TGHU1000014, type: 20ft, gross_mass_kg: 22000, slot: [12, 2, 2]",
               "exercise.containers[2].type", "the holds have 40 ft cells");
  expect_error("slot: [12, 2, 82]", "slot: [12, 2, 82], center_of_mass_m: [7.0, 0, 0]",
               "exercise.containers[2].center_of_mass_m", "outside the container");
  expect_error("keel_midship_m: [31.0,", "keel_midship_m: [25.0,", "exercise.vessel.keel_midship_m",
               "overlaps the quay");
  expect_error("to: truck", "to: trailer", "exercise.moves[0].to", "only 'truck'");
  expect_error("machine: ../machines/sts.yaml", "machine: ../machines/nowhere.yaml", "exercise.machine",
               "no such file");
  expect_error("trolley_x_m: 32.27", "trolley_x_m: 99.0", "exercise.crane.trolley_x_m", "outside");
  expect_error("{id: TGHU1000014,", "{id: TGHU1000010,", "exercise.containers[2].id", "duplicate container");
  expect_error("hard_landing: 5,", "hard_landings: 5,", "exercise.rules.deductions.hard_landings",
               "unknown deduction");
  expect_error("hard_landing: 5,", "hard_landing: 500,", "exercise.rules.deductions.hard_landing", "outside");
  // the error lists every deduction an exercise may set (the vehicles' ones too)
  for (const RuleField& field : rule_deductions())
    expect_error("hard_landing: 5,", "hard_landings: 5,", "exercise.rules.deductions.hard_landings",
                 std::string(field.key));
  expect_error("hard_landing: 5,", "hard_landings: 5,", "exercise.rules.deductions.hard_landings",
               "speeding");
  // stowage: boxes stand on the box below them
  expect_error("slot: [12, 3, 82]", "slot: [12, 3, 84]", "exercise.containers[0].slot",
               "nothing stowed under it in tier 82");
  expect_error("slot: [12, 1, 82]", "slot: [12, 3, 82]", "exercise.containers[1].slot",
               "two containers in one slot");
  // four high cubes (11.58 m) do not fit in the 11.5 m hold: the fourth, three lines further down, is named
  const std::string text = shipped();
  const std::string from = "{id: TGHU1000014, type: 40ft, gross_mass_kg: 22000, slot: [12, 2, 82]}";
  scenes::expect_data_error(
      text, from,
      "{id: HC02, type: 40ftHC, gross_mass_kg: 22000, slot: [12, 2, 2]}\n"
      "    - {id: HC04, type: 40ftHC, gross_mass_kg: 22000, slot: [12, 2, 4]}\n"
      "    - {id: HC06, type: 40ftHC, gross_mass_kg: 22000, slot: [12, 2, 6]}\n"
      "    - {id: HC08, type: 40ftHC, gross_mass_kg: 22000, slot: [12, 2, 8]}",
      [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
      scenes::line_of(text, from) + 3, "exercise.containers[5].slot", "into the hatch covers");
}

// Each rubric key sets the figure it names (the designer's forms and the loader share the table).
TEST(ExerciseFiles, TheSignallersRadioCallsLoadInOrderAndABadOneIsNamed) {
  const sim::ExerciseSettings rtg = load_exercise(HARBOUR_DATA_DIR "/exercises/rtg_truck_to_block.yaml");
  EXPECT_EQ(rtg.radio.language, "en");
  ASSERT_EQ(rtg.radio.calls.size(), 2u);
  EXPECT_EQ(rtg.radio.calls[1].at_s, 45.0);
  EXPECT_EQ(rtg.radio.calls[1].text, "Row four, tier three. Mind the stack on row five.");
  EXPECT_TRUE(load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml").radio.calls.empty());
  const std::string radio =
      "  radio:\n    language: de\n    calls:\n      - {at_s: 5, say: langsam heben}\n"
      "      - {at_s: 9, say: halt}\n  moves:";
  const std::string text = shipped();
  const auto with_radio = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find("  moves:"), 8, radio);
    const std::size_t at = t.find(from);
    if (at != std::string::npos) t.replace(at, from.size(), to);
    try {
      load_exercise(YamlFile::parse(t, "exercise.yaml"), HARBOUR_DATA_DIR "/exercises");
    } catch (const DataError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(with_radio("", ""), "");
  EXPECT_NE(
      with_radio("language: de", "language: German").find("exercise.radio.language: an espeak-ng voice"),
      std::string::npos);
  EXPECT_NE(
      with_radio("at_s: 9", "at_s: 4").find("exercise.radio.calls[1].at_s: comes before the call before it"),
      std::string::npos);
  EXPECT_NE(with_radio("say: halt", "said: halt").find("exercise.radio.calls[1]"), std::string::npos);
}

TEST(ExerciseFiles, EachRubricKeySetsTheFigureItNames) {
  std::string text = shipped();
  const std::string from = "deductions: {collision: 10,";
  text.replace(text.find(from), from.size(),
               "harsh_jerk_mps3: 12.5\n    overtime_s: 90\n    deductions: {collision: 11, speeding: 7, "
               "jackknife: 9, decimetre_above_trim: 4, landing_while_swaying: 3,");
  const sim::EvaluationRules r =
      load_exercise(YamlFile::parse(text, "rubric.yaml"), HARBOUR_DATA_DIR "/exercises").rules;
  EXPECT_EQ(r.harsh_jerk_mps3, 12.5);
  EXPECT_EQ(r.overtime_s, 90.0);
  EXPECT_EQ(r.time_limit_s, 180.0);
  EXPECT_EQ(r.points_collision, 11.0);
  EXPECT_EQ(r.points_overspeed, 7.0);
  EXPECT_EQ(r.points_jackknife, 9.0);
  EXPECT_EQ(r.points_per_trim_dm, 4.0);
  EXPECT_EQ(r.points_sway, 3.0);
  EXPECT_EQ(r.points_hard_landing, 5.0);
  EXPECT_EQ(r.points_tip_over, sim::EvaluationRules{}.points_tip_over);  // not set: the default
}

// The designer's start pose is the loader's: each number of it, for every machine, is read from the key it
// names, within its range, and refused past it with its field named.
TEST(ExerciseFiles, TheStartPoseFormIsWhatTheLoaderReads) {
  for (const char* name : {"sts_discharge", "rtg_rehandle", "mhc_coal_discharge", "mhc_hook_lift",
                           "reach_stacker_stack", "tractor_mafi_park"}) {
    SCOPED_TRACE(name);
    const std::string file = std::string(HARBOUR_DATA_DIR) + "/exercises/" + name + ".yaml";
    const StartPoseForm form = start_pose_form(load_exercise(file).scenario.machine);
    EXPECT_FALSE(form.fields.empty());
    const YAML::Node shipped = YAML::LoadFile(file);
    for (const StartPoseField& field : form.fields) {
      if (field.component >= 0) continue;
      const std::string where = "exercise." + form.section + "." + field.key;
      SCOPED_TRACE(where);
      EXPECT_TRUE(field.optional || shipped["exercise"][form.section][field.key])
          << "a key the loader requires";
      const auto load_with = [&](double value) {
        YAML::Node edited = YAML::Clone(shipped);
        edited["exercise"][form.section][field.key] = value;
        YAML::Emitter out;
        out << edited;
        return load_exercise(YamlFile::parse(out.c_str(), "pose.yaml"), HARBOUR_DATA_DIR "/exercises");
      };
      const double middle = (field.min + field.max) / 2;
      const sim::ExerciseSettings moved = load_with(middle);
      const StartPoseForm again = start_pose_form(moved.scenario.machine);
      EXPECT_EQ(again.fields.size(), form.fields.size());
      try {
        load_with(field.max + 1.0 + std::abs(field.max) * 1e-3);
        ADD_FAILURE() << "a start past the range loads";
      } catch (const DataError& e) {
        EXPECT_EQ(e.field(), where);
      }
    }
  }
}

// ISO 668 boxes by their cargo: the type's typical tare (reference.md) unless the file gives one.
TEST(ExerciseFiles, AContainersGrossMassIsTarePlusCargo) {
  std::string text = shipped();
  const std::string from = "{id: TGHU1000010, type: 40ft, gross_mass_kg: 22000,";
  text.replace(text.find(from), from.size(), "{id: TGHU1000010, type: 40ft, cargo_mass_kg: 18000,");
  const std::string from2 = "{id: TGHU1000014, type: 40ft, gross_mass_kg: 22000,";
  text.replace(text.find(from2), from2.size(),
               "{id: TGHU1000014, type: 40ft, cargo_mass_kg: 18000, tare_kg: 4100,");
  const sim::ExerciseSettings e =
      load_exercise(YamlFile::parse(text, "cargo.yaml"), HARBOUR_DATA_DIR "/exercises");
  EXPECT_DOUBLE_EQ(e.scenario.containers[0].gross_mass_kg, 3750.0 + 18000.0);
  EXPECT_DOUBLE_EQ(e.scenario.containers[2].gross_mass_kg, 4100.0 + 18000.0);
  EXPECT_DOUBLE_EQ(e.scenario.containers[1].gross_mass_kg, 22000.0);
  expect_error("{id: TGHU1000012, type: 40ft, gross_mass_kg: 22000,",
               "{id: TGHU1000012, type: 40ft, gross_mass_kg: 22000, cargo_mass_kg: 100,",
               "exercise.containers[1]", "either gross_mass_kg or cargo_mass_kg");
  expect_error("{id: TGHU1000012, type: 40ft, gross_mass_kg: 22000,",
               "{id: TGHU1000012, type: 40ft, cargo_mass_kg: 39000,", "exercise.containers[1].cargo_mass_kg",
               "outside");
}

// A high cube is a foot taller than a tier: the box stowed on it stands on its roof, not in mid-air or in it.
TEST(ExerciseFiles, StowedBoxesStandOnTheBoxBelow) {
  std::string text = shipped();
  const std::string from = "{id: TGHU1000010, type: 40ft, gross_mass_kg: 22000, slot: [12, 3, 82]}";
  text.replace(text.find(from), from.size(),
               "{id: TGHU1000010, type: 40ftHC, gross_mass_kg: 22000, slot: [12, 3, 82]}\n"
               "    - {id: TGHU1000016, type: 40ft, gross_mass_kg: 22000, slot: [12, 3, 84]}");
  const sim::ExerciseSettings e =
      load_exercise(YamlFile::parse(text, "stack.yaml"), HARBOUR_DATA_DIR "/exercises");
  const auto& hc = e.scenario.containers[0];
  const auto& on_it = e.scenario.containers[1];
  EXPECT_NEAR(hc.half_extents_m.z, 2.896 / 2, 1e-9);
  EXPECT_NEAR(on_it.pose.position.z - hc.pose.position.z, 2.896 / 2 + 2.591 / 2, 1e-9);
  EXPECT_NEAR(on_it.pose.position.x, hc.pose.position.x, 1e-9);
}

}  // namespace
}  // namespace harbour::io

namespace harbour::io {
namespace {

// Strictness: a file the instructor mistyped is refused, never run as a different exercise.
TEST(ExerciseFiles, UnknownDuplicateAndOutOfRangeKeysNameFileLineAndField) {
  expect_error(
      "    time_limit_s: 180", "    time_limit: 180", "exercise.rules.time_limit",
      "unknown key 'time_limit' (known here: body_contact_impulse_ns, collision_speed_mps, deductions");
  expect_error("    pass_score: 70", "    pass_score: 70\n    pass_score: 90", "exercise.rules.pass_score",
               "duplicate key (first given at line", 1);
  expect_error("  quay_edge_x_m: 18.0", "  weather: {wind_mean: 70}\n  quay_edge_x_m: 18.0",
               "exercise.weather.wind_mean", "unknown key 'wind_mean'");
  expect_error("  quay_edge_x_m: 18.0", "  weather: {wind_mean_mps: 75}\n  quay_edge_x_m: 18.0",
               "exercise.weather.wind_mean_mps", "75 is outside [0, 50]");
  expect_error("  quay_edge_x_m: 18.0", "  weather: {cloud_oktas: 9}\n  quay_edge_x_m: 18.0",
               "exercise.weather.cloud_oktas", "9 is outside [0, 8]");
  expect_error("  quay_edge_x_m: 18.0", "  weather: 5\n  quay_edge_x_m: 18.0", "exercise.weather",
               "expected a mapping");
  expect_error("gantry_y_m: 0.0", "gantry_y_m: 1e300", "exercise.crane.gantry_y_m",
               "1e+300 is outside [-200, 200]");
  expect_error("{container: TGHU1000012, to: truck, tolerance_m: 0.3}",
               "{container: TGHU1000012, to: truck}\n    - {container: TGHU1000012, to: truck}",
               "exercise.moves[1].container", "is already moved by exercise.moves[0]", 1);
  expect_error("id: TGHU1000010", "id: \"TGHU\\n1000010\"", "exercise.containers[0].id",
               "the name holds a control character");
  expect_error("  name: sts_discharge", "  name: sts\xc3\x28", "exercise.name", "is not valid UTF-8");
  expect_error("  name: sts_discharge", "  name: " + std::string(300, 'x'), "exercise.name",
               "is 300 bytes long (at most 256)");
}

TEST(ExerciseFiles, ASecondDocumentOrAFileThatIsNotOneIsRefused) {
  EXPECT_THROW(load_exercise(YamlFile::parse(shipped() + "---\nexercise: {}\n", "two.yaml"),
                             HARBOUR_DATA_DIR "/exercises"),
               DataError);
  for (const char* path : {"/dev/zero", "/tmp", "/nonexistent.yaml"}) {
    try {
      load_exercise(path);
      FAIL() << "read " << path;
    } catch (const DataError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_EQ(e.field(), "(file)");
    }
  }
}

TEST(ExerciseFiles, LoadingGrowsLinearlyWithTheContainers) {
  // 2000 boxes on the quay and 500 moves (the limits): the look-ups are by map, not by scanning
  std::string text =
      "exercise:\n  name: many\n  machine: ../machines/sts.yaml\n"
      "  crane: {gantry_y_m: 0, trolley_x_m: 20, spreader_z_m: 20}\n  containers:\n";
  std::string moves = "  moves:\n";
  for (int n = 0; n < 2000; ++n) {
    const std::string id = "BOX" + std::to_string(n);
    text += "    - {id: " + id + ", type: 20ft, gross_mass_kg: 20000, position_m: [" +
            std::to_string(n % 40 * 3) + ", " + std::to_string(n / 40 * 7) + ", 1.3]}\n";
    if (n < 500) moves += "    - {container: " + id + ", target_m: [0, 0, 1.3]}\n";  // the most moves
  }
  const auto start = std::chrono::steady_clock::now();
  const sim::ExerciseSettings e =
      load_exercise(YamlFile::parse(text + moves, "many.yaml"), HARBOUR_DATA_DIR "/exercises");
  EXPECT_EQ(e.moves.size(), 500u);
  // a quadratic loader took seconds here; generous for a slow sanitizer build
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  EXPECT_THROW(load_exercise(YamlFile::parse(text +
                                                 "    - {id: ONEMORE, type: 20ft, gross_mass_kg: 20000, "
                                                 "position_m: [0, -50, 1.3]}\n" +
                                                 moves,
                                             "too_many.yaml"),
                             HARBOUR_DATA_DIR "/exercises"),
               DataError);
}

}  // namespace
}  // namespace harbour::io

namespace harbour::io {
namespace {

// ISO 6346's check digit: the standard's own example (CSQU305438 3), a box seen in service (MSKU907032 3) and
// a zero serial worked by hand.
TEST(ExerciseFiles, AContainerCodesCheckDigitIsIso6346s) {
  EXPECT_EQ(iso6346_code("CSQU", 305438), "CSQU3054383");
  EXPECT_EQ(iso6346_code("MSKU", 907032), "MSKU9070323");
  EXPECT_EQ(iso6346_code("TGHU", 0),
            "TGHU0000008");  // T31 G17 H18 U32: 31 + 34 + 72 + 256 = 393, 393 mod 11 = 8
}

}  // namespace
}  // namespace harbour::io
