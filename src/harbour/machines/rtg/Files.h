#pragma once

#include <string>

#include "harbour/io/MachineFileType.h"
#include "harbour/machines/rtg/RubberTyredGantry.h"

namespace harbour::io {

/// Reads an RTG file (data/machines/rtg.yaml); its hoist reeving is read relative to `folder`.
sim::RtgSettings load_rtg(const YamlFile& file, const std::string& folder);
sim::RtgSettings load_rtg(const std::string& path);

/// How a rubber-tyred gantry is read from files: its machine file and its exercises' start block.
const MachineFileType& rtg_machine_files();

}  // namespace harbour::io
