#include "harbour/io/ExerciseFiles.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "scenes/DataErrors.h"

namespace harbour::io {
namespace {

std::string shipped() {
  return scenes::read_text(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
}

void expect_error(const std::string& from, const std::string& to, const std::string& field,
                  const std::string& says) {
  const std::string text = shipped();
  scenes::expect_data_error(
      text, from, to, [](const YamlFile& f) { load_exercise(f, HARBOUR_DATA_DIR "/exercises"); },
      scenes::line_of(text, from), field, says);
}

TEST(ExerciseFiles, ShippedDischargeLoads) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  EXPECT_EQ(e.name, "sts_discharge");
  ASSERT_EQ(e.scenario.containers.size(), 3u);
  EXPECT_DOUBLE_EQ(e.scenario.containers[1].half_extents_m.x, 12.192 / 2);  // ISO 668 40 ft
  ASSERT_EQ(e.moves.size(), 1u);
  EXPECT_EQ(e.moves[0].container_id, "BOX2");
  EXPECT_EQ(e.rules.time_limit_s, 180.0);
}

TEST(ExerciseFiles, WeatherAndEventsLoad) {
  const sim::ExerciseSettings e = load_exercise(HARBOUR_DATA_DIR "/exercises/sts_discharge_gusty.yaml");
  EXPECT_EQ(e.scenario.weather.wind_mean_mps, 10.0);
  EXPECT_NEAR(e.scenario.weather.wind_from_rad, 3.14159265358979, 1e-9);
  ASSERT_EQ(e.scenario.events.size(), 1u);
  EXPECT_EQ(e.scenario.events[0].kind, sim::ScriptedEvent::Kind::kGust);
  EXPECT_EQ(e.scenario.events[0].gust.amplitude_mps, 8.0);
}

TEST(ExerciseFiles, BadExercisesNameTheField) {
  expect_error("type: 40ft, gross_mass_kg: 22000, position_m: [42.0, 0.0",
               "type: 53ft, gross_mass_kg: 22000, position_m: [42.0, 0.0", "exercise.containers[1].type",
               "unknown container type '53ft'");
  expect_error("container: BOX2", "container: BOX9", "exercise.moves[0].container", "no container 'BOX9'");
  expect_error("machine: ../machines/sts.yaml", "machine: ../machines/rtg.yaml", "exercise.machine",
               "no such file");
  expect_error("trolley_x_m: 42.0", "trolley_x_m: 99.0", "exercise.crane.trolley_x_m", "outside");
  expect_error("{id: BOX3,", "{id: BOX1,", "exercise.containers[2].id", "duplicate container");
}

}  // namespace
}  // namespace harbour::io
