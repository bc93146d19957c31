#pragma once

// A mobile harbour crane on the quay with its grab hanging open, for the machine's tests.

#include <string>

#include "harbour/machines/mhc/Files.h"
#include "harbour/sim/Simulation.h"

namespace harbour::scenes {

/// The shipped MHC (data/machines/mhc.yaml) standing at the origin, boom at 0.8 rad, the grab head at 20 m.
inline sim::MhcSetup mhc_setup(const std::string& data_dir) {
  sim::MhcSetup setup;
  setup.crane = io::load_mhc(data_dir + "/machines/mhc.yaml");
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
