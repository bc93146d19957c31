#pragma once

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"

namespace harbour::test {

/// Each machine kind's controls as its shipped machine file declares them (read through the first of its
/// shipped exercises by name): what device mappings are written for.
inline std::map<std::string, scene::ControlTable> shipped_machine_controls() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(HARBOUR_DATA_DIR "/exercises"))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::map<std::string, scene::ControlTable> tables;
  for (const std::filesystem::path& file : files) {
    const sim::ExerciseSettings exercise = io::load_exercise(file.string());
    tables.emplace(exercise.scenario.machine.kind(), exercise.scenario.machine.controls());
  }
  return tables;
}

}  // namespace harbour::test
