#pragma once

// A mobile harbour crane on the quay with its grab hanging open, for the machine's tests.

#include <string>

#include "harbour/io/ReevingFiles.h"
#include "harbour/sim/Simulation.h"

namespace harbour::scenes {

/// The MHC's shipped reevings on the default settings, standing at the origin, boom at 0.8 rad, the grab
/// head at 20 m.
inline sim::MhcSetup mhc_setup(const std::string& data_dir) {
  sim::MhcSetup setup;
  setup.crane.luffing = io::load_reeving(data_dir + "/reeving/boom_luffing.yaml").reeving;
  setup.crane.hoist = io::load_reeving(data_dir + "/reeving/mhc_grab.yaml").reeving;
  setup.crane.slew_drive = {0.126, 0.025, 0.025, 0.08, 4.0e6, 6.0e6, -1e9, 1e9};  // 1.2 rpm (assumed)
  setup.start = {{0.0, 0.0, 0.0}, 0.0, 0.8, 20.0};
  return setup;
}

/// A quay with the MHC and nothing else.
inline sim::ScenarioSettings mhc_on_quay(const std::string& data_dir) {
  sim::ScenarioSettings s;
  s.name = "mhc_on_quay";
  s.machine = mhc_setup(data_dir);
  return s;
}

}  // namespace harbour::scenes
