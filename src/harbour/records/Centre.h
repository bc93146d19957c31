#pragma once

#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/records/RecordsStore.h"

namespace harbour::records {

/// The shipped data folder (data/: machines, exercises, routes, visuals, sounds, teams).
std::string shipped_data_folder();

/// A training centre's own folders: the exercises its designer saves and the routes its instructors write,
/// searched by name before the shipped data/exercises and data/routes ("" : none of its own).
struct CentreFolders {
  std::string exercises;
  std::string routes;

  /// The centre's folder (when it has one), then the shipped one.
  std::vector<std::string> exercise_folders() const;
  std::vector<std::string> route_folders() const;
};

/// The default records database: $XDG_DATA_HOME/harboursim/records.db (or ~/.local/share/...), as a SOCI
/// connection string.
std::string default_database();

/// An exercise file: `name_or_path` itself when it is a file, else `<name>.yaml` in the centre's exercise
/// folder (when given: the designer's), then the shipped `data/exercises`. With `version` (an attempt's): the
/// version the designer kept (`versions/<name>-<version>.yaml`) when the exercise has changed since. Throws
/// naming what it tried and the exercises there are.
std::string resolve_exercise(const std::string& name_or_path, const std::string& centre = "",
                             const std::string& version = "");
/// Loads what resolve_exercise found: a version the designer kept (in the folder's `versions/`) as if it
/// stood in the folder itself, where its relative paths (../machines/...) were written for.
sim::ExerciseSettings load_resolved_exercise(const std::string& file);

/// The exercise a stored attempt ran, to replay or continue it: the records' copy of its version, else the
/// file of that version (the current one, or one the designer kept). Where neither is left, the current file
/// with `inexact` saying in words that the replay may not be what the trainee had (else `inexact` is "").
io::ExerciseSource attempt_exercise(RecordsStore& db, const AttemptRow& attempt,
                                    const std::string& centre_exercises, std::string& inexact);

}  // namespace harbour::records
