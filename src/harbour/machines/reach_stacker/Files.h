#pragma once

#include <string>

#include "harbour/io/MachineFileType.h"
#include "harbour/machines/reach_stacker/ReachStacker.h"
#include "harbour/machines/reach_stacker/ReachStackerStability.h"

namespace harbour::io {

/// Reads a reach stacker file (data/machines/reach_stacker.yaml): masses, axles, tyres, boom, rotator, load
/// chart.
sim::ReachStackerSettings load_reach_stacker(const YamlFile& file);
sim::ReachStackerSettings load_reach_stacker(const std::string& path);

/// How a reach stacker is read from files: its machine file and its exercises' start block.
const MachineFileType& reach_stacker_machine_files();

}  // namespace harbour::io
