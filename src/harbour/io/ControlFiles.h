#pragma once

#include <string>

#include "harbour/io/YamlFile.h"
#include "harbour/scene/Controls.h"

namespace harbour::io {

/// A machine's `controls:` list: each entry's label, kind (axis, button, switch), range or positions,
/// neutral and safe values and meaning. Errors name the file, line and field.
scene::ControlTable read_control_table(const YamlFile& file, const YAML::Node& parent,
                                       const std::string& path);

}  // namespace harbour::io
