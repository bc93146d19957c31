#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "harbour/sim/Evaluation.h"

namespace harbour::apps {

/// A line of an exercise the console's designer saved (its last): the designer may overwrite only these (a
/// shipped exercise stays as it is).
inline constexpr const char* kDesignedMarker = "# designed in the harboursim console";
bool designed(const std::string& text);

/// A design (an exercise's YAML text) checked by the simulator's own exercise loader as if it were saved in
/// the centre's exercise folder (its relative paths, ../machines/..., resolve from there).
struct DesignCheck {
  sim::ExerciseSettings exercise;
  std::string text;     ///< as it would be saved (the marker last)
  std::string version;  ///< the content hash attempts will record (io::exercise_version)
};

/// Checks a design; throws std::invalid_argument with the loader's error (file, line and field, the file
/// named "the design") when it is not a valid exercise, or when it has no exercise name a file can take.
DesignCheck check_design(const std::string& folder, const std::string& yaml);

/// Saves a checked design as FOLDER/NAME.yaml (NAME: its exercise name), written beside and renamed over, and
/// keeps the version as FOLDER/versions/NAME-VERSION.yaml, so a replay of an attempt of an earlier version
/// still finds what it ran. Throws std::logic_error when NAME is an exercise the designer did not make.
/// Returns the file saved.
std::string save_design(const std::string& folder, const DesignCheck& design);

/// What the designer's forms need of a checked design beyond its YAML: the machine's start pose (its keys and
/// ranges, io::start_pose_form), the vessel's bays, rows (port to
/// starboard) and tiers and the yard block's slots to click, the rubric's figures as in force (defaults where
/// the design sets none) with their ranges, the scripted events this machine takes, and the vessel files and
/// bulk materials beside the centre's exercise folder to choose from.
nlohmann::json design_form(const std::string& folder, const DesignCheck& design);

/// The text of an exercise in `folder` by name, to start a design from; std::out_of_range when none.
std::string design_source(const std::string& folder, const std::string& name);

}  // namespace harbour::apps
