#pragma once

#include <array>
#include <span>
#include <string>

#include "harbour/sim/Simulation.h"

namespace harbour::io {

/// An instructor command written as text, for the command line and scripts:
/// `AT:KIND[:VALUES]` with AT in seconds of exercise time and KIND one of
///   gust:AMPLITUDE_MPS:DURATION_S, hoist-brake-fault, landed-sensor-fault:CORNER, limiter-fault,
///   clear-faults, emergency-stop, release-emergency-stop, power-failure, power-restored,
///   wind:MEAN_MPS:FROM_DEG:TURBULENCE,
///   visibility:METRES, rain:MM_PER_H, time-of-day:HOURS.
/// A kind may be spelt with underscores as exercise files write it (`hoist_brake_fault`).
/// Longest command text read, and the latest time a command may be set for (a day) [s].
inline constexpr std::size_t kMaxCommandBytes = 200;
inline constexpr double kMaxCommandTime_s = 86400.0;

struct TimedCommand {
  double at_s = 0.0;
  sim::InstructorCommand command;
};

/// Each kind of instructor command as the command line, the console, the stations and the records name it,
/// with the values it takes in order: the one table every reader and writer of the names uses.
struct CommandKindText {
  sim::InstructorCommand::Kind kind;
  const char* name;                   ///< "hoist-brake-fault"
  std::array<const char*, 3> values;  ///< what each value is ("mean speed [m/s]"), nullptr past the last
};
std::span<const CommandKindText> command_kinds();
/// The name of a kind of command ("landed-sensor-fault").
const char* command_name(sim::InstructorCommand::Kind kind);
/// The same name as exercise files write it, its words joined by underscores ("landed_sensor_fault").
std::string file_spelling(sim::InstructorCommand::Kind kind);

/// Parses one (plain decimal numbers, the ranges of sim::why_invalid); throws std::invalid_argument quoting
/// the text (control characters escaped) and saying what is wrong.
TimedCommand parse_instructor_command(const std::string& text);

}  // namespace harbour::io
