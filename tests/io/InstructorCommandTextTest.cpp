#include "harbour/io/InstructorCommandText.h"

#include "harbour/core/Text.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

namespace harbour::io {
namespace {

using Kind = sim::InstructorCommand::Kind;

TEST(InstructorCommandText, ParsesEveryKind) {
  const TimedCommand gust = parse_instructor_command("45.5:gust:8:3");
  EXPECT_EQ(gust.at_s, 45.5);
  EXPECT_EQ(gust.command.kind, Kind::kGust);
  EXPECT_EQ(gust.command.gust.amplitude_mps, 8.0);
  EXPECT_EQ(gust.command.gust.duration_s, 3.0);
  EXPECT_EQ(parse_instructor_command("60:hoist-brake-fault").command.kind, Kind::kHoistBrakeFault);
  EXPECT_EQ(parse_instructor_command("60:landed-sensor-fault:2").command.corner, 2);
  EXPECT_EQ(parse_instructor_command("90:clear-faults").command.kind, Kind::kClearFaults);
  const TimedCommand wind = parse_instructor_command("0:wind:12:270:0.15");
  EXPECT_EQ(wind.command.wind_mean_mps, 12.0);
  EXPECT_NEAR(wind.command.wind_from_rad, 1.5 * 3.14159265358979, 1e-12);
  EXPECT_EQ(wind.command.turbulence, 0.15);
  EXPECT_EQ(parse_instructor_command("0:visibility:300").command.value, 300.0);
  EXPECT_EQ(parse_instructor_command("0:rain:8").command.kind, Kind::kSetRain);
  EXPECT_EQ(parse_instructor_command("0:cloud:6").command.kind, Kind::kSetCloud);
  EXPECT_EQ(parse_instructor_command("0:cloud:6").command.value, 6.0);
  EXPECT_NE(why_refused("cloud:9").find("cloud cover [oktas] is outside 0-8"), std::string::npos);
  EXPECT_EQ(parse_instructor_command("0:time-of-day:21.5").command.value, 21.5);
}

// The table of names is the parser's: every kind has one name, and written with its values it reads back
// as that kind.
TEST(InstructorCommandText, EveryKindHasOneNameThatReadsBackAsIt) {
  std::set<std::string> names;
  for (std::uint8_t n = 0; n < sim::InstructorCommand::kKinds; ++n) {
    const Kind kind = static_cast<Kind>(n);
    const std::string name = command_name(kind);
    EXPECT_TRUE(names.insert(name).second) << name << " twice";
    std::string text = "1:" + name;
    for (const CommandText& c : station_commands())
      if (c.kind == kind)
        for (const CommandValue& value : c.values)
          if (value.what) text += value.hand_signal ? ":lower" : ":1";
    EXPECT_EQ(parse_instructor_command(text).command.kind, kind) << text;
  }
  // a hand signal by its name, its index the value
  EXPECT_EQ(parse_instructor_command("5:signal:hoist-slowly").command.value, 4.0);
  EXPECT_EQ(why_refused("signal:stop"), "");
  EXPECT_NE(why_refused("signal:wave").find("hoist-slowly"), std::string::npos);
  EXPECT_NE(why_refused("signal").find("hand signal"), std::string::npos);
  EXPECT_STREQ(command_name(Kind::kHoistBrakeFault), "hoist-brake-fault");
  // the exercise files' spelling of the same names, read too
  EXPECT_EQ(file_spelling(Kind::kLandedSensorFault), "landed_sensor_fault");
  EXPECT_EQ(parse_instructor_command("60:hoist_brake_fault").command.kind, Kind::kHoistBrakeFault);
  EXPECT_EQ(parse_instructor_command("60:landed_sensor_fault:3").command.corner, 3);
}

void expect_rejected(const std::string& text, const std::string& says) {
  try {
    parse_instructor_command(text);
    FAIL() << "accepted " << text;
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'" + core::printable(text, 100) + "'"), std::string::npos)
        << what;  // quoted, escaped  // quotes what was given
    EXPECT_NE(what.find(says), std::string::npos) << what;
  }
}

TEST(InstructorCommandText, BadCommandsSayWhatIsWrong) {
  expect_rejected("10:gale:9", "unknown kind 'gale'");
  expect_rejected("soon:gust:8:3", "time [s] is not a decimal number");
  expect_rejected("-5:clear-faults", "the time is outside 0-86400 s");
  // what the exercise files forbid, the command line forbids too
  expect_rejected("1e300:clear-faults", "the time is outside 0-86400 s");
  expect_rejected("0x10:clear-faults", "time [s] is not a decimal number");
  expect_rejected("inf:clear-faults", "time [s] is not a decimal number");
  expect_rejected("10:gust:-8:3", "the gust amplitude [m/s] is outside 0-30 (not 0)");
  expect_rejected("10:gust:31:3", "the gust amplitude [m/s] is outside 0-30 (not 0)");
  expect_rejected("10:wind:51:90:0.1", "the wind speed [m/s] is outside 0-50");
  expect_rejected("10:wind:12:400:0.1", "the wind from [deg] is outside 0-360");
  expect_rejected("10:\x1b[31mgale", "unknown kind '\\x1B[31mgale'");
  expect_rejected(std::string(300, '1'), "longer than 200 characters");
  expect_rejected("10:gust:8", "missing gust duration [s]");
  expect_rejected("10:gust:8:3:4", "too many values");
  expect_rejected("10:landed-sensor-fault:7", "the corner is outside 0-3");
  expect_rejected("10:landed-sensor-fault:1.5", "whole number");
  expect_rejected("10:visibility:-1", "visibility");
  expect_rejected("10:time-of-day:25", "the time of day [h] is outside 0-24 (not 24)");
  expect_rejected("10", "missing the kind");
}

// The table's ranges are the simulation's: each end of a value's range is taken or refused by why_invalid as
// the table says (a table wider than the simulation would offer forms the station refuses, a narrower one
// hide what the simulation can do).
TEST(InstructorCommandText, TheTablesRangesAreTheSimulations) {
  int ends = 0;
  for (const CommandText& c : station_commands()) {
    if (!c.kind) continue;
    for (std::size_t k = 0; k < c.values.size() && c.values[k].what; ++k) {
      const CommandValue& v = c.values[k];
      if (v.hand_signal) continue;  // a name, not a number (above)
      for (const bool upper : {false, true}) {
        const double end = upper ? v.max : v.min;
        const double past = upper ? end + std::max(1e-6, 1e-9 * std::abs(end)) : end - 1e-6;
        for (const double x : {end, past}) {
          sim::InstructorCommand command;
          command.kind = *c.kind;
          // the values at the table's initial, the one tried at x
          double values[3];
          for (std::size_t n = 0; n < 3; ++n)
            values[n] = n == k ? x : c.values[n].initial;
          command.gust.amplitude_mps = values[0];
          command.gust.duration_s = values[1];
          command.corner = static_cast<int>(values[0]);
          command.value = values[0];
          command.wind_mean_mps = values[0];
          command.wind_from_rad = values[1] * 3.14159265358979323846 / 180.0;
          command.turbulence = values[2];
          if (c.kind == Kind::kLandedSensorFault && x != std::floor(x)) continue;  // not a corner's number
          const bool taken = sim::why_invalid(command).empty();
          const bool table_takes = x == end && !(upper ? v.below_max : v.above_min);
          EXPECT_EQ(taken, table_takes) << c.name << " " << v.what << " at " << x;
          ++ends;
        }
      }
    }
  }
  EXPECT_GE(ends, 30);
}

TEST(InstructorCommandText, AStationCommandIsOneOfTheTablesWithItsValuesInRange) {
  for (const std::string ok : {"start", "hold", "stop", "wind:12:270:0.15", "hoist-brake-fault", "volume:80",
                               "radio:hoist up slowly", "radio:ease: down", "mute"})
    EXPECT_EQ(why_refused(ok), "") << ok;
  const std::pair<std::string, std::string> refused[] = {
      {"gale", "no command 'gale' (start, hold,"},
      {"take-over", "no command 'take-over'"},  // a replay's, with its recording: not a bare command
      {"volume:250", "volume:volume [%], 0-200"},
      {"volume:loud", "volume:volume [%], 0-200"},
      {"radio:   ", "some words"},
      {"radio:" + std::string(43, 'a'), "at most 42 characters"},
      {"hold:5", "hold takes no value"},
      {"wind:80:270:0.1", "wind speed [m/s] is outside 0-50"},
      {"limiter-fault:1", "too many values"},
  };
  for (const auto& [text, says] : refused)
    EXPECT_NE(why_refused(text).find(says), std::string::npos) << text << ": " << why_refused(text);
}

TEST(InstructorCommandText, EveryCommandHasOneNameALabelAndItsValuesSaid) {
  std::set<std::string> names, labels;
  for (const CommandText& c : station_commands()) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_TRUE(labels.insert(c.label).second) << c.label;
    EXPECT_STRNE(group_name(c.group), "?");
    for (const CommandValue& v : c.values)
      if (v.what && !v.words) {
        EXPECT_TRUE(v.min <= v.initial && v.initial <= v.max && v.step > 0) << c.name;
      }
  }
}

}  // namespace
}  // namespace harbour::io
