#pragma once

#include <cstdint>
#include <string>

#include "harbour/records/Centre.h"

namespace harbour::station {

/// `harboursim station`: a trainee runs an exercise live at the station.
struct StationOptions {
  std::string exercise;             ///< file or name (in the centre's folder, then the shipped ones)
  records::CentreFolders centre;    ///< the centre's exercises and routes (none: only the shipped ones)
  std::string route;                ///< or a training route: its next stage for the trainee
  std::string profile = "desktop";  ///< desktop, medium, immersive or a profile file
  std::string trainee;              ///< "" : autopilot with --autopilot, else guest (both made on first use)
  std::string record;
  std::string database;
  bool autopilot = false;           ///< the scripted operator drives (a demonstration, no devices needed)
  double time_scale = 1.0;          ///< an instructor's fast-forward
  double seconds = 0.0;             ///< stop after this much wall time (0: at the exercise's end)
  std::string window = "auto";      ///< the trainee's window: on, off, auto (where there is a display)
  std::string sound = "auto";       ///< the cab's sound: on, off, auto (with the window)
  std::string name;                 ///< the station's name on the centre's network ("": not on it)
  int domain = 0;                   ///< the centre's DDS domain
  bool serve = false;               ///< wait for consoles to start exercises, one after another
  std::string team;                 ///< a team file or a shipped team's name: this station is one member
  std::string role;                 ///< its role in the team (its exercise is the role's)
  std::string take_over_recording;  ///< continue this recording's attempt live (a console's take-over)
  std::int64_t take_over_step = 0;
};
int run_station(const StationOptions& options);

}  // namespace harbour::station
