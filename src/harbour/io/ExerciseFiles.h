#pragma once

#include <map>
#include <string>
#include <vector>

#include "harbour/io/MachineFileType.h"
#include "harbour/io/YamlFile.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::io {

/// Reads an exercise file (data/exercises/*.yaml): the machine it names (a path relative to the exercise's
/// folder), static blocks, containers by ISO 668 type, the moves to make and the evaluation rules.
sim::ExerciseSettings load_exercise(const YamlFile& file, const std::string& folder);
sim::ExerciseSettings load_exercise(const std::string& path);

/// An ISO 6346 container code: the owner code and equipment category (four letters, "CSQU"), the six-digit
/// serial and the check digit computed from them ("CSQU3054383").
std::string iso6346_code(const std::string& owner_and_category, int serial);

/// An ISO 668 container type exercises name (20ft, 40ft, 40ftHC, 45ftHC): its external dimensions [m] and
/// typical tare [kg].
struct IsoType {
  core::Vec3 size_m;
  double tare_kg;
};
const std::map<std::string, IsoType>& iso_types();

/// The kinds of scripted event an exercise for a machine of this type may hold, as its file names them: a
/// gust, and a failure of each part the machine has (its type's faults).
std::vector<std::string> event_kinds(const sim::MachineType& type);
/// The faults an instructor can inject into a machine of this type, as the console and the command line name
/// the commands ("hoist-brake-fault"): a failure of each part it has.
std::vector<std::string> instructor_faults(const sim::MachineType& type);

/// A figure of an exercise's rubric by its key under exercise.rules (a threshold) or
/// exercise.rules.deductions (points per occurrence), with the range the loader accepts (open at min when
/// `above_min`).
struct RuleField {
  const char* key;
  double sim::EvaluationRules::*value;
  double min, max;
  bool above_min;
};
const std::vector<RuleField>& rule_thresholds();
const std::vector<RuleField>& rule_deductions();

/// The start pose the loader reads for this machine (its settings loaded; the MHC on its grab or its hook as
/// set): one table for the loader and the designer's forms.
StartPoseForm start_pose_form(const sim::MachineSetup& machine);

/// The names of the exercises in `folder` (the stems of its *.yaml files, hidden ones not), sorted; none for
/// a missing folder.
std::vector<std::string> exercise_names(const std::string& folder);

/// What the console's lists show of an exercise file without loading its machine and scene: its name, its
/// machine's kind and what it says of itself (exercise.about).
struct ExerciseCard {
  std::string name, machine;
  std::optional<sim::ExerciseAbout> about;
  std::string error;  ///< set when the file cannot be read so far (the rest is then what could be read)
};
ExerciseCard read_exercise_card(const std::string& file);
/// The cards of the exercises in these folders (a name in two: the first folder's), by name.
std::vector<ExerciseCard> exercise_cards(const std::vector<std::string>& folders);
/// Why an exercise may not take this title: another exercise in these folders (one not named `except`, the
/// exercise itself) has it, whatever the case of its ASCII letters; "" when it may.
std::string why_title_taken(const std::vector<std::string>& folders, const std::string& title,
                            const std::string& except);

/// The exercise file's version: the first 16 hex digits of the SHA-256 of its bytes. Attempts store it, so
/// results stay comparable when an exercise is edited (the machine and vessel files it names are not
/// hashed). Throws DataError when the file cannot be read.
std::string exercise_version(const std::string& path);
/// The version of an exercise file's text (as exercise_version hashes its bytes).
std::string exercise_text_version(const std::string& text);

/// An exercise as an attempt runs it: its file's text and the folder its relative paths (../machines/...)
/// resolve from. The records keep it by its version, so a replay re-simulates exactly what the trainee had
/// however the file changes later.
struct ExerciseSource {
  std::string file;    ///< where it was read (named in errors)
  std::string folder;  ///< where its relative paths resolve from
  std::string text;
  std::string version;  ///< exercise_text_version(text)
};
/// Reads an exercise file; a version the designer kept (in a folder's versions/) resolves its paths from the
/// folder above, where it was written for. Throws DataError when it cannot be read.
ExerciseSource read_exercise_source(const std::string& file);
/// Loads an exercise from its source (errors name source.file).
sim::ExerciseSettings load_exercise_source(const ExerciseSource& source);

}  // namespace harbour::io
