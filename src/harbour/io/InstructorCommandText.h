#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "harbour/sim/Simulation.h"

namespace harbour::io {

/// An instructor command written as text, for the command line and scripts:
/// `AT:KIND[:VALUES]` with AT in seconds of exercise time and KIND one of
///   gust:AMPLITUDE_MPS:DURATION_S, hoist-brake-fault, landed-sensor-fault:CORNER, limiter-fault,
///   clear-faults, emergency-stop, release-emergency-stop, power-failure, power-restored,
///   wind:MEAN_MPS:FROM_DEG:TURBULENCE,
///   visibility:METRES, rain:MM_PER_H, time-of-day:HOURS, signal:NAME (a hand signal: hoist, stop, ...).
/// A kind may be spelt with underscores as exercise files write it (`hoist_brake_fault`).
/// Longest command text read, and the latest time a command may be set for (a day) [s].
inline constexpr std::size_t kMaxCommandBytes = 200;
inline constexpr double kMaxCommandTime_s = 86400.0;

struct TimedCommand {
  double at_s = 0.0;
  sim::InstructorCommand command;
};

/// What a command is for: the console's panel groups its buttons so.
/// (kStop: what stops the machine at once; kRestart: what lets it go again.)
/// (kSignal: what the signaller shows the operator.)
enum class CommandGroup : std::uint8_t { kSession, kWeather, kFault, kStop, kRestart, kSound, kSignal };
/// "session", "weather", "fault", "stop", "restart", "sound", "signal"
const char* group_name(CommandGroup group);

/// One value a command takes: a number within its range, or words.
struct CommandValue {
  const char* what = nullptr;  ///< "mean speed" (nullptr: past the last value)
  const char* unit = "";       ///< "m/s"
  double min = 0.0;            ///< the least it may be (itself refused where above_min)
  double max = 0.0;      ///< the most it may be (itself refused where below_max); words: the most characters
  double initial = 0.0;  ///< what the console's form offers first
  double step = 1.0;     ///< the console form's step
  bool above_min = false, below_max = false;
  bool words = false;        ///< free words (a radio call)
  bool hand_signal = false;  ///< a hand signal's name (scene::hand_signals(); its index is the value)
};

/// Each command an instructor gives a station, as the command line, the console, its designer, the stations
/// and the records name it, with the values it takes in order and their ranges: the one table every reader
/// and writer of the names uses.
struct CommandText {
  const char* name;   ///< "hoist-brake-fault"
  const char* label;  ///< "Hoist brake fault": its button's words
  CommandGroup group;
  /// The simulation's command it gives (none: the station's own, as start, hold or the sound's volume).
  std::optional<sim::InstructorCommand::Kind> kind;
  std::array<CommandValue, 3> values{};
};
std::span<const CommandText> station_commands();
/// Why a station command written as text ("wind:12:270:0.15", "volume:80", "radio:hoist up slowly") is not
/// one of the table's with its values in range ("" when it is).
std::string why_refused(const std::string& command);
/// The name of a kind of command ("landed-sensor-fault").
const char* command_name(sim::InstructorCommand::Kind kind);
/// The same name as exercise files write it, its words joined by underscores ("landed_sensor_fault").
std::string file_spelling(sim::InstructorCommand::Kind kind);

/// Parses one (plain decimal numbers, the ranges of sim::why_invalid); throws std::invalid_argument quoting
/// the text (control characters escaped) and saying what is wrong.
TimedCommand parse_instructor_command(const std::string& text);

}  // namespace harbour::io
