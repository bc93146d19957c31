#include "harbour/io/InstructorCommandText.h"

#include "harbour/core/Text.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

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
    for (const CommandKindText& k : command_kinds())
      if (k.kind == kind)
        for (const char* value : k.values)
          if (value) text += ":1";
    EXPECT_EQ(parse_instructor_command(text).command.kind, kind) << text;
  }
  EXPECT_EQ(command_kinds().size(), sim::InstructorCommand::kKinds);
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
  expect_rejected("10:gust:-8:3", "peaks at 0-30 m/s");
  expect_rejected("10:gust:31:3", "peaks at 0-30 m/s");
  expect_rejected("10:wind:51:90:0.1", "wind 0-50 m/s");
  expect_rejected("10:wind:12:400:0.1", "direction is outside 0-360 deg");
  expect_rejected("10:\x1b[31mgale", "unknown kind '\\x1B[31mgale'");
  expect_rejected(std::string(300, '1'), "longer than 200 characters");
  expect_rejected("10:gust:8", "missing duration");
  expect_rejected("10:gust:8:3:4", "too many values");
  expect_rejected("10:landed-sensor-fault:7", "corner is 0-3");
  expect_rejected("10:landed-sensor-fault:1.5", "whole number");
  expect_rejected("10:visibility:-1", "visibility");
  expect_rejected("10:time-of-day:25", "time of day");
  expect_rejected("10", "missing the kind");
}

}  // namespace
}  // namespace harbour::io
