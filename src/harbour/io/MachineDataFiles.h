#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "harbour/io/YamlFile.h"

namespace harbour::io {

/// What the image generator and the sound read from machine files beside the physics (a machine's looks and
/// sounds), found without naming a machine: the shipped machine file of each kind
/// (`data_folder`/machines/<kind>.yaml; the registry's kinds, from the caller) and, where given, an
/// exercise's own machine file after them.
std::vector<std::string> machine_data_files(const std::string& data_folder,
                                            std::span<const std::string_view> kinds,
                                            const std::string& machine_file = "");

/// A machine file read for one of its sections, with its kind (`machine.kind`).
struct MachineDataFile {
  std::string kind;
  YamlFile file;
};
/// The files read, one per kind in the order the kinds first appear; of several files of one kind the last
/// (an exercise's own machine file after the shipped one). Throws DataError naming a file without a kind.
std::vector<MachineDataFile> load_machine_data_files(const std::vector<std::string>& files);

}  // namespace harbour::io
