#pragma once

#include <string>

#include "harbour/io/YamlFile.h"
#include "harbour/sim/Vessel.h"

namespace harbour::io {

/// Reads a vessel file (data/vessels/*.yaml): hull, rows, tiers, 40 ft bays, cell guides, hatch covers.
sim::VesselSettings load_vessel(const YamlFile& file);
sim::VesselSettings load_vessel(const std::string& path);

/// A sea-state harmonic's ranges: amplitudes up to these (heave [m], roll and pitch [deg]), periods [s].
struct HarmonicRange {
  double max_heave_m = 5.0, max_angle_deg = 10.0, min_period_s = 0.5, max_period_s = 120.0;
};
inline constexpr HarmonicRange kHarmonicRange{};

/// Reads a sea state (heave, roll, pitch harmonics, each within kHarmonicRange) at `node`; `at` names it in
/// errors.
sim::SeaState read_sea_state(const YamlFile& file, const YAML::Node& node, const std::string& at);

}  // namespace harbour::io
