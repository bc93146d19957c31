#pragma once

#include <string>

#include "harbour/io/MachineFileType.h"
#include "harbour/machines/straddle_carrier/StraddleCarrier.h"

namespace harbour::io {

/// Reads a straddle carrier file (data/machines/straddle_carrier.yaml): its portal, wheels, drivetrain, the
/// spreader hoist (its reeving relative to `folder`) and cab.
sim::StraddleCarrierSettings load_straddle_carrier(const YamlFile& file, const std::string& folder);
sim::StraddleCarrierSettings load_straddle_carrier(const std::string& path);
/// How a straddle carrier is read from files: its machine file and its exercises' start block.
const MachineFileType& straddle_carrier_machine_files();

}  // namespace harbour::io
