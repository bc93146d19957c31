#pragma once

#include <string>

#include "harbour/io/MachineFileType.h"
#include "harbour/machines/tractor/TerminalTractor.h"

namespace harbour::io {

/// Reads a terminal tractor file (data/machines/tractor.yaml).
sim::TractorSettings load_tractor(const YamlFile& file);
sim::TractorSettings load_tractor(const std::string& path);
/// A trailer file (data/trailers): its tare mass (an exercise adds the payload), deck, kingpin, axles, tyres,
/// brakes and legs.
sim::TrailerSettings load_trailer(const YamlFile& file);
sim::TrailerSettings load_trailer(const std::string& path);

/// How a terminal tractor is read from files: its machine file and its exercises' start block.
const MachineFileType& tractor_machine_files();

}  // namespace harbour::io
