#pragma once

#include <string>

#include "harbour/io/MachineFileType.h"
#include "harbour/machines/sts/StsCrane.h"

namespace harbour::io {

/// Reads an STS crane file (data/machines/sts.yaml) and the hoist reeving it names (a path relative to the
/// machine file's folder).
sim::StsCraneSettings load_sts_crane(const YamlFile& file, const std::string& folder);
sim::StsCraneSettings load_sts_crane(const std::string& path);

/// How an STS crane is read from files: its machine file and its exercises' start block.
const MachineFileType& sts_machine_files();

}  // namespace harbour::io
