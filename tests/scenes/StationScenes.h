#pragma once

// What the station's tests and benchmarks share: scratch files and a records database with a trainee in it,
// and virtual SDL flight sticks like those the shipped desk mapping binds.

#include <SDL.h>

#include <filesystem>
#include <string>

#include "harbour/records/RecordsStore.h"

namespace harbour::scenes {

/// A path in the temporary folder.
inline std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

/// A new SQLite records database in the temporary folder holding trainee "t1"; its connection string.
inline std::string fresh_database(const std::string& name) {
  const std::string path = temp_path(name);
  std::filesystem::remove(path);
  records::RecordsStore("sqlite3://db=" + path).ensure_trainee("t1", "Trainee One");
  return "sqlite3://db=" + path;
}

/// Attaches a Thrustmaster T.16000M-like virtual flight stick (x, y, twist, throttle; 16 buttons; a hat) and
/// returns its device index (negative on failure, SDL_GetError says why). SDL's joysticks must be
/// initialised.
inline int attach_flight_stick() {
  SDL_VirtualJoystickDesc desc{};
  desc.version = SDL_VIRTUAL_JOYSTICK_DESC_VERSION;
  desc.type = SDL_JOYSTICK_TYPE_FLIGHT_STICK;
  desc.naxes = 4;
  desc.nbuttons = 16;
  desc.nhats = 1;
  desc.name = "Thrustmaster T.16000M";
  return SDL_JoystickAttachVirtualEx(&desc);
}

}  // namespace harbour::scenes
