#pragma once

#include <string>

#include "harbour/io/YamlFile.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"
#include "harbour/machines/reach_stacker/ReachStackerStability.h"
#include "harbour/machines/rtg/RubberTyredGantry.h"
#include "harbour/machines/sts/StsCrane.h"
#include "harbour/machines/tractor/TerminalTractor.h"

namespace harbour::io {

/// Reads an STS crane file (data/machines/sts.yaml) and the hoist reeving it names (a path relative to the
/// machine file's folder).
sim::StsCraneSettings load_sts_crane(const YamlFile& file, const std::string& folder);
sim::StsCraneSettings load_sts_crane(const std::string& path);
/// Reads a mobile harbour crane file (data/machines/mhc.yaml) and the luffing and hoist reevings it names.
sim::MhcSettings load_mhc(const YamlFile& file, const std::string& folder);
sim::MhcSettings load_mhc(const std::string& path);
/// Reads a terminal tractor file (data/machines/tractor.yaml).
sim::TractorSettings load_tractor(const YamlFile& file);
sim::TractorSettings load_tractor(const std::string& path);
/// A trailer file (data/trailers): its tare mass (an exercise adds the payload), deck, kingpin, axles, tyres,
/// brakes and legs.
sim::TrailerSettings load_trailer(const YamlFile& file);
sim::TrailerSettings load_trailer(const std::string& path);
/// A reach stacker file (data/machines/reach_stacker.yaml): masses, axles, tyres, boom, rotator, load chart.
sim::ReachStackerSettings load_reach_stacker(const YamlFile& file);
sim::ReachStackerSettings load_reach_stacker(const std::string& path);
/// An RTG file (data/machines/rtg.yaml); its hoist reeving is read relative to `folder`.
sim::RtgSettings load_rtg(const YamlFile& file, const std::string& folder);
sim::RtgSettings load_rtg(const std::string& path);
/// The kind a machine file declares (`machine.kind`: sts, rtg, mhc, tractor, reach_stacker); throws
/// DataError naming the field.
std::string machine_file_kind(const std::string& path);

}  // namespace harbour::io
