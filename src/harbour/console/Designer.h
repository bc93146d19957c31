#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "harbour/records/Centre.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/training/Route.h"

namespace harbour::console {

/// A line of an exercise the console's designer saved, or of a route its route editor saved (their last): the
/// console may overwrite only these (a shipped exercise or route stays as it is).
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
/// still finds what it ran. Throws std::logic_error when NAME is an exercise the designer did not make, or a
/// shipped exercise's name.
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

/// A route written in the console's route editor, checked by the simulator's own route loader as the file
/// ID.yaml in the centre's route folder (errors name it so): its stages name the centre's exercises or the
/// shipped ones.
struct RouteCheck {
  training::Route route;
  std::string text;  ///< as it would be saved (the marker last)
};
/// Checks a route; throws std::invalid_argument with the loader's error, or when ID is no file name.
RouteCheck check_route_text(const records::CentreFolders& centre, const std::string& id,
                            const std::string& yaml);
/// Saves a checked route in the centre's route folder (the first of centre.route_folders()), written beside
/// and renamed over. Throws std::logic_error when its name is a shipped route's or a route the editor did not
/// write. Returns the file saved.
std::string save_route(const records::CentreFolders& centre, const RouteCheck& route);
/// The text of a route by name (the centre's, then the shipped ones), to start from; std::out_of_range when
/// none.
std::string route_source(const records::CentreFolders& centre, const std::string& id);

}  // namespace harbour::console
