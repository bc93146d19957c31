#include "harbour/io/InstructorCommandText.h"

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

}  // namespace

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
  using Kind = sim::InstructorCommand::Kind;
  TimedCommand t;
  t.at_s = number(0, "time [s]");
  if (!(t.at_s >= 0.0 && t.at_s <= kMaxCommandTime_s)) fail("the time is outside 0-86400 s (a day)");
  if (parts.size() < 2) fail("missing the kind");
  const std::string& kind = parts[1];
  std::size_t values = 0;
  sim::InstructorCommand& c = t.command;
  if (kind == "gust") {
    c.kind = Kind::kGust;
    c.gust.amplitude_mps = number(2, "amplitude [m/s]");
    c.gust.duration_s = number(3, "duration [s]");
    values = 2;
  } else if (kind == "hoist-brake-fault") {
    c.kind = Kind::kHoistBrakeFault;
  } else if (kind == "landed-sensor-fault") {
    c.kind = Kind::kLandedSensorFault;
    const double corner = number(2, "corner (0-3)");
    if (corner != std::floor(corner)) fail("the corner is a whole number 0-3");
    c.corner = static_cast<int>(corner);
    values = 1;
  } else if (kind == "limiter-fault") {
    c.kind = Kind::kLimiterFault;
  } else if (kind == "clear-faults") {
    c.kind = Kind::kClearFaults;
  } else if (kind == "emergency-stop") {
    c.kind = Kind::kEmergencyStop;
  } else if (kind == "release-emergency-stop") {
    c.kind = Kind::kReleaseEmergencyStop;
  } else if (kind == "power-failure") {
    c.kind = Kind::kPowerFailure;
  } else if (kind == "power-restored") {
    c.kind = Kind::kPowerRestored;
  } else if (kind == "wind") {
    c.kind = Kind::kSetWind;
    c.wind_mean_mps = number(2, "mean speed [m/s]");
    const double from_deg = number(3, "direction it blows from [deg]");
    if (!(from_deg >= 0.0 && from_deg <= 360.0)) fail("the direction is outside 0-360 deg");
    c.wind_from_rad = core::deg_to_rad(from_deg);
    c.turbulence = number(4, "turbulence intensity");
    values = 3;
  } else if (kind == "visibility" || kind == "rain" || kind == "time-of-day") {
    c.kind = kind == "visibility" ? Kind::kSetVisibility
             : kind == "rain"     ? Kind::kSetRain
                                  : Kind::kSetTimeOfDay;
    c.value = number(2, kind == "visibility" ? "visibility [m]"
                        : kind == "rain"     ? "rain [mm/h]"
                                             : "time [h]");
    values = 1;
  } else {
    fail("unknown kind '" + core::printable(kind, 40) +
         "' (gust, hoist-brake-fault, landed-sensor-fault, limiter-fault, clear-faults, emergency-stop, "
         "release-emergency-stop, power-failure, power-restored, wind, visibility, rain, time-of-day)");
  }
  if (parts.size() > 2 + values) fail("too many values for '" + kind + "'");
  if (const std::string why = sim::why_invalid(c); !why.empty()) fail(why);
  return t;
}

}  // namespace harbour::io
