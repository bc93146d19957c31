#pragma once

#include <string>
#include <vector>

#include "harbour/cable/Reeving.h"
#include "harbour/io/YamlFile.h"

namespace harbour::io {

/// A reeving file (data/reeving/*.yaml): the reeving and the names of the bodies its mounts refer to
/// (mount body i is bodies[i]; "world" is fixed).
struct ReevingFile {
  cable::ReevingSettings reeving;
  std::vector<std::string> bodies;
};

/// Reads and checks a reeving: known bodies, rope types and elements; every rope starts at a drum, runs over
/// sheaves only and ends at an anchor or drum; no sheave carries two ropes; positive sizes.
ReevingFile load_reeving(const YamlFile& file);
ReevingFile load_reeving(const std::string& path);

}  // namespace harbour::io
