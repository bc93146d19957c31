#pragma once

#include <string>

#include "harbour/io/YamlFile.h"
#include "harbour/sim/Vessel.h"

namespace harbour::io {

/// Reads a vessel file (data/vessels/*.yaml): hull, rows, tiers, 40 ft bays, cell guides, hatch covers.
sim::VesselSettings load_vessel(const YamlFile& file);
sim::VesselSettings load_vessel(const std::string& path);

/// Reads a sea state (heave, roll, pitch harmonics) at `node`; `at` names it in errors.
sim::SeaState read_sea_state(const YamlFile& file, const YAML::Node& node, const std::string& at);

}  // namespace harbour::io
