#pragma once

#include <string>

#include "harbour/io/YamlFile.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::io {

/// Reads an exercise file (data/exercises/*.yaml): the machine it names (a path relative to the exercise's
/// folder), static blocks, containers by ISO 668 type, the moves to make and the evaluation rules.
sim::ExerciseSettings load_exercise(const YamlFile& file, const std::string& folder);
sim::ExerciseSettings load_exercise(const std::string& path);

}  // namespace harbour::io
