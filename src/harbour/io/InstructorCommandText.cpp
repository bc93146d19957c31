#include "harbour/io/InstructorCommandText.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "harbour/core/Text.h"
#include "harbour/core/Units.h"
#include "harbour/scene/HandSignals.h"

namespace harbour::io {
namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts(1);
  for (char c : text) {
    if (c == ':')
      parts.emplace_back();
    else
      parts.back() += c;
  }
  return parts;
}

using Kind = sim::InstructorCommand::Kind;
using Group = CommandGroup;
// a value within [min, max]: what, unit, min, max, initial, step (and where an end itself is refused)
constexpr CommandValue number(const char* what, const char* unit, double min, double max, double initial,
                              double step) {
  return {what, unit, min, max, initial, step};
}
constexpr CommandValue above(CommandValue v) {
  v.above_min = true;
  return v;
}
constexpr CommandValue below(CommandValue v) {
  v.below_max = true;
  return v;
}
constexpr CommandValue kWords{.what = "radio call", .max = 42, .words = true};

constexpr CommandText kCommands[] = {
    {"start", "Start", Group::kSession, std::nullopt, {}},
    {"hold", "Hold", Group::kSession, std::nullopt, {}},
    {"resume", "Resume", Group::kSession, std::nullopt, {}},
    {"step", "Step", Group::kSession, std::nullopt, {}},
    {"reset", "Reset", Group::kSession, std::nullopt, {}},
    {"stop", "Stop", Group::kSession, std::nullopt, {}},
    {"wind",
     "Set wind",
     Group::kWeather,
     Kind::kSetWind,
     {number("wind speed", "m/s", 0, sim::kMaxMeanWind_mps, 12, 0.5),
      number("wind from", "deg", 0, 360, 270, 5), number("turbulence intensity", "", 0, 1, 0.15, 0.05)}},
    {"gust",
     "Gust",
     Group::kWeather,
     Kind::kGust,
     {above(number("gust amplitude", "m/s", 0, sim::kMaxGust_mps, 8, 1)),
      above(number("gust duration", "s", 0, sim::kMaxGustDuration_s, 3, 1))}},
    {"visibility",
     "Set visibility",
     Group::kWeather,
     Kind::kSetVisibility,
     {above(number("visibility", "m", 0, sim::kMaxVisibility_m, 300, 10))}},
    {"rain",
     "Set rain",
     Group::kWeather,
     Kind::kSetRain,
     {number("rain", "mm/h", 0, sim::kMaxRain_mm_per_h, 8, 1)}},
    {"cloud",
     "Set cloud",
     Group::kWeather,
     Kind::kSetCloud,
     {number("cloud cover", "oktas", 0, sim::kOvercast_oktas, 6, 1)}},
    {"time-of-day",
     "Set time",
     Group::kWeather,
     Kind::kSetTimeOfDay,
     {below(number("time of day", "h", 0, sim::kHoursPerDay, 21.5, 0.5))}},
    {"hoist-brake-fault", "Hoist brake fault", Group::kFault, Kind::kHoistBrakeFault, {}},
    {"landed-sensor-fault",
     "Landed sensor fault",
     Group::kFault,
     Kind::kLandedSensorFault,
     {number("corner", "", 0, sim::kTwistlockCorners - 1, 2, 1)}},
    {"limiter-fault", "Limiter fault", Group::kFault, Kind::kLimiterFault, {}},
    {"clear-faults", "Clear faults", Group::kFault, Kind::kClearFaults, {}},
    {"emergency-stop", "Emergency stop", Group::kStop, Kind::kEmergencyStop, {}},
    {"release-emergency-stop", "Release stop", Group::kRestart, Kind::kReleaseEmergencyStop, {}},
    {"power-failure", "Power failure", Group::kStop, Kind::kPowerFailure, {}},
    {"power-restored", "Power back", Group::kRestart, Kind::kPowerRestored, {}},
    {"mute", "Mute", Group::kSound, std::nullopt, {}},
    {"unmute", "Unmute", Group::kSound, std::nullopt, {}},
    {"volume", "Set volume", Group::kSound, std::nullopt, {number("volume", "%", 0, 200, 100, 10)}},
    {"radio", "Call", Group::kSound, std::nullopt, {kWords}},
    {"signal",
     "Signal",
     Group::kSignal,
     Kind::kSignal,
     {CommandValue{.what = "hand signal", .hand_signal = true}}},
};
constexpr std::size_t simulation_commands() {
  std::size_t n = 0;
  for (const CommandText& c : kCommands)
    n += c.kind.has_value();
  return n;
}
static_assert(simulation_commands() == sim::InstructorCommand::kKinds, "a name for every kind");

std::size_t value_count(const CommandText& c) {
  std::size_t n = 0;
  while (n < c.values.size() && c.values[n].what)
    ++n;
  return n;
}

std::string value_name(const CommandValue& v) {
  return *v.unit ? std::string(v.what) + " [" + v.unit + "]" : std::string(v.what);
}

std::string range_text(const CommandValue& v) {
  std::ostringstream out;
  out << v.min << "-" << v.max;
  if (v.above_min) out << " (not " << v.min << ")";
  if (v.below_max) out << " (not " << v.max << ")";
  return out.str();
}

// plain decimal numbers only, as in the exercise files (no hex, inf or nan)
std::optional<double> decimal(const std::string& p) {
  const bool digits = !p.empty() && p.find_first_not_of("0123456789.-+eE") == std::string::npos &&
                      std::isdigit(static_cast<unsigned char>(p.back())) != 0;
  if (!digits) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(p.c_str(), &end);
  if (*end != '\0' || !std::isfinite(v)) return std::nullopt;
  return v;
}

bool in_range(const CommandValue& v, double x) {
  return (v.above_min ? x > v.min : x >= v.min) && (v.below_max ? x < v.max : x <= v.max);
}

const CommandText* find_command(const std::string& name) {
  for (const CommandText& c : kCommands)
    if (name == c.name) return &c;
  return nullptr;
}

std::string known_names(bool simulation_only) {
  std::string names;
  for (const CommandText& c : kCommands)
    if (!simulation_only || c.kind) names += std::string(names.empty() ? "" : ", ") + c.name;
  return names;
}

}  // namespace

const char* group_name(CommandGroup group) {
  switch (group) {
    case Group::kSession:
      return "session";
    case Group::kWeather:
      return "weather";
    case Group::kFault:
      return "fault";
    case Group::kStop:
      return "stop";
    case Group::kRestart:
      return "restart";
    case Group::kSound:
      return "sound";
    case Group::kSignal:
      return "signal";
  }
  return "?";
}

std::span<const CommandText> station_commands() {
  return kCommands;
}

const char* command_name(Kind kind) {
  for (const CommandText& c : kCommands)
    if (c.kind == kind) return c.name;
  return "?";
}

std::string file_spelling(Kind kind) {
  std::string name = command_name(kind);
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

std::string why_refused(const std::string& command) {
  const std::size_t colon = command.find(':');
  const std::string name = command.substr(0, colon);
  const CommandText* known = find_command(name);
  if (!known) return "no command '" + core::printable(name, 40) + "' (" + known_names(false) + ")";
  if (known->kind) {
    try {
      parse_instructor_command("0:" + command);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }
  const std::size_t values = value_count(*known);
  const std::string rest = colon == std::string::npos ? "" : command.substr(colon + 1);
  if (values == 0) return colon == std::string::npos ? "" : name + " takes no value";
  const CommandValue& v = known->values[0];  // the station's own commands take one value at most
  if (v.words) {
    if (rest.find_first_not_of(' ') == std::string::npos) return name + ":" + v.what + " (some words to say)";
    if (rest.size() > static_cast<std::size_t>(v.max))
      return name + ": at most " + std::to_string(static_cast<int>(v.max)) + " characters";
    return "";
  }
  const std::optional<double> x = decimal(rest);
  if (!x || !in_range(v, *x)) return name + ":" + value_name(v) + ", " + range_text(v);
  return "";
}

TimedCommand parse_instructor_command(const std::string& text) {
  auto fail = [&](const std::string& why) -> void {
    throw std::invalid_argument("instructor command '" + core::printable(text, 100) + "': " + why);
  };
  if (text.size() > kMaxCommandBytes) fail("longer than " + std::to_string(kMaxCommandBytes) + " characters");
  const std::vector<std::string> parts = split(text);
  auto number = [&](std::size_t k, const std::string& what) {
    if (k >= parts.size()) fail("missing " + what);
    const std::optional<double> v = decimal(parts[k]);
    if (!v) fail(what + " is not a decimal number");
    return *v;
  };
  TimedCommand t;
  t.at_s = number(0, "time [s]");
  if (!(t.at_s >= 0.0 && t.at_s <= kMaxCommandTime_s)) fail("the time is outside 0-86400 s (a day)");
  if (parts.size() < 2) fail("missing the kind");
  std::string kind = parts[1];
  std::replace(kind.begin(), kind.end(), '_', '-');  // as exercise files spell it
  const CommandText* known = find_command(kind);
  if (!known || !known->kind)
    fail("unknown kind '" + core::printable(kind, 40) + "' (" + known_names(true) + ")");
  const std::size_t values = value_count(*known);
  double v[3] = {0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < values; ++k) {
    const CommandValue& value = known->values[k];
    if (value.hand_signal) {
      const int signal = 2 + k < parts.size() ? scene::find_hand_signal(parts[2 + k]) : -1;
      if (signal < 0) fail("the hand signal is one of " + scene::hand_signal_names());
      v[k] = signal;
      continue;
    }
    v[k] = number(2 + k, value_name(value));
    if (!in_range(value, v[k])) fail("the " + value_name(value) + " is outside " + range_text(value));
  }
  sim::InstructorCommand& c = t.command;
  c.kind = *known->kind;
  switch (c.kind) {
    case Kind::kGust:
      c.gust.amplitude_mps = v[0];
      c.gust.duration_s = v[1];
      break;
    case Kind::kLandedSensorFault:
      if (v[0] != std::floor(v[0])) fail("the corner is a whole number 0-3");
      c.corner = static_cast<int>(v[0]);
      break;
    case Kind::kSetWind:
      c.wind_mean_mps = v[0];
      c.wind_from_rad = core::deg_to_rad(v[1]);
      c.turbulence = v[2];
      break;
    case Kind::kSetVisibility:
    case Kind::kSetRain:
    case Kind::kSetCloud:
    case Kind::kSetTimeOfDay:
    case Kind::kSignal:
      c.value = v[0];
      break;
    default:
      break;
  }
  if (parts.size() > 2 + values) fail("too many values for '" + kind + "'");
  if (const std::string why = sim::why_invalid(c); !why.empty()) fail(why);
  return t;
}

}  // namespace harbour::io
