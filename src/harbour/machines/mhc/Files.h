#pragma once

#include <string>

#include "harbour/io/MachineFileType.h"
#include "harbour/machines/mhc/MobileHarbourCrane.h"

namespace harbour::io {

/// Reads a mobile harbour crane file (data/machines/mhc.yaml) and the luffing and hoist reevings it names.
sim::MhcSettings load_mhc(const YamlFile& file, const std::string& folder);
sim::MhcSettings load_mhc(const std::string& path);

/// How a mobile harbour crane is read from files: its machine file and its exercises' start block.
const MachineFileType& mhc_machine_files();

}  // namespace harbour::io
