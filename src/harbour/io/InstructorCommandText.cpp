#include "harbour/io/InstructorCommandText.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "harbour/core/Text.h"
#include "harbour/core/Units.h"

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
constexpr CommandKindText kCommandKinds[] = {
    {Kind::kGust, "gust", {"amplitude [m/s]", "duration [s]", nullptr}},
    {Kind::kHoistBrakeFault, "hoist-brake-fault", {}},
    {Kind::kLandedSensorFault, "landed-sensor-fault", {"corner (0-3)", nullptr, nullptr}},
    {Kind::kClearFaults, "clear-faults", {}},
    {Kind::kSetWind, "wind", {"mean speed [m/s]", "direction it blows from [deg]", "turbulence intensity"}},
    {Kind::kSetVisibility, "visibility", {"visibility [m]", nullptr, nullptr}},
    {Kind::kSetRain, "rain", {"rain [mm/h]", nullptr, nullptr}},
    {Kind::kSetTimeOfDay, "time-of-day", {"time [h]", nullptr, nullptr}},
    {Kind::kLimiterFault, "limiter-fault", {}},
    {Kind::kEmergencyStop, "emergency-stop", {}},
    {Kind::kReleaseEmergencyStop, "release-emergency-stop", {}},
    {Kind::kPowerFailure, "power-failure", {}},
    {Kind::kPowerRestored, "power-restored", {}},
};
static_assert(std::size(kCommandKinds) == sim::InstructorCommand::kKinds, "a name for every kind");

}  // namespace

std::span<const CommandKindText> command_kinds() {
  return kCommandKinds;
}

const char* command_name(Kind kind) {
  for (const CommandKindText& k : kCommandKinds)
    if (k.kind == kind) return k.name;
  return "?";
}

std::string file_spelling(Kind kind) {
  std::string name = command_name(kind);
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

TimedCommand parse_instructor_command(const std::string& text) {
  auto fail = [&](const std::string& why) -> void {
    throw std::invalid_argument("instructor command '" + core::printable(text, 100) + "': " + why);
  };
  if (text.size() > kMaxCommandBytes) fail("longer than " + std::to_string(kMaxCommandBytes) + " characters");
  const std::vector<std::string> parts = split(text);
  auto number = [&](std::size_t k, const char* what) {
    if (k >= parts.size()) fail(std::string("missing ") + what);
    // plain decimal numbers only, as in the exercise files (no hex, inf or nan)
    const std::string& p = parts[k];
    const bool decimal = !p.empty() && p.find_first_not_of("0123456789.-+eE") == std::string::npos &&
                         std::isdigit(static_cast<unsigned char>(p.back())) != 0;
    char* end = nullptr;
    const double v = decimal ? std::strtod(p.c_str(), &end) : 0.0;
    if (!decimal || *end != '\0' || !std::isfinite(v)) fail(std::string(what) + " is not a decimal number");
    return v;
  };
  TimedCommand t;
  t.at_s = number(0, "time [s]");
  if (!(t.at_s >= 0.0 && t.at_s <= kMaxCommandTime_s)) fail("the time is outside 0-86400 s (a day)");
  if (parts.size() < 2) fail("missing the kind");
  std::string kind = parts[1];
  std::replace(kind.begin(), kind.end(), '_', '-');  // as exercise files spell it
  const CommandKindText* known = nullptr;
  for (const CommandKindText& k : kCommandKinds)
    if (kind == k.name) known = &k;
  if (!known) {
    std::string names;
    for (const CommandKindText& k : kCommandKinds)
      names += std::string(names.empty() ? "" : ", ") + k.name;
    fail("unknown kind '" + core::printable(kind, 40) + "' (" + names + ")");
  }
  std::size_t values = 0;
  double v[3] = {0.0, 0.0, 0.0};
  for (; values < known->values.size() && known->values[values]; ++values)
    v[values] = number(2 + values, known->values[values]);
  sim::InstructorCommand& c = t.command;
  c.kind = known->kind;
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
      if (!(v[1] >= 0.0 && v[1] <= 360.0)) fail("the direction is outside 0-360 deg");
      c.wind_mean_mps = v[0];
      c.wind_from_rad = core::deg_to_rad(v[1]);
      c.turbulence = v[2];
      break;
    case Kind::kSetVisibility:
    case Kind::kSetRain:
    case Kind::kSetTimeOfDay:
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
