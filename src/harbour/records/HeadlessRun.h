#pragma once

#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/records/Centre.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::records {

/// `harboursim run`: an exercise headless with the autopilot, progress lines and the evaluation.
struct RunOptions {
  std::string exercise;           ///< exercise file, or an exercise's name (records::resolve_exercise)
  records::CentreFolders centre;  ///< the centre's exercises and routes (none: only the shipped ones)
  bool autopilot = false;
  std::string record;                 ///< recording file to write ("" for none)
  std::string trainee = "autopilot";  ///< trainee id the attempt is stored under
  std::string database;               ///< records connection ("" for the default SQLite file)
  std::vector<std::string>
      commands;  ///< instructor commands, AT:KIND[:VALUES] (io::parse_instructor_command)
  /// a training route (data/routes): the trainee, enrolled in it, runs its next stage's exercise
  std::string route;
  std::string stage;  ///< set by the run: the route's stage it runs
  io::ExerciseSource
      source;  ///< set by the run: the exercise as it runs (kept in the records by its version)
};
/// Returns 0 when the exercise ended (passed, failed, or ended by the instructor), kExitOutOfTime when its
/// time limit and overtime ran out with goals left, 3 when the physics diverged, 130 on a signal, 1 with
/// physics warnings.
int run_exercise(const RunOptions& options);
inline constexpr int kExitOutOfTime = 4;

/// Everything a run writes, checked before it starts (a bad output never costs a whole exercise).
void check_outputs(const RunOptions& options);
/// The evaluation as the trainee reads it: every figure the records store of the attempt (those every machine
/// has and its machine's own) in words, what each move, landing and bite was, and the score.
void print_evaluation(const sim::Metrics& metrics, const sim::Score& score);

/// `harboursim replay`: re-simulates a recording, checks every recorded second's hash, prints the evaluation.
int replay_recording(const std::string& recording, const std::string& exercise);
/// `harboursim replay --attempt N`: the same for a stored attempt, from the records alone where they keep its
/// recording (else its file), on the exercise version it ran (the centre's folder `centre_exercises` first).
int replay_attempt(std::int64_t attempt, const std::string& database, const std::string& centre_exercises);

/// `harboursim replay --take-over <s>`: an instructor takes over the recording at that moment; the run goes
/// on live from exactly the recorded state (the autopilot drives: no input devices yet), stored as a new
/// attempt linked to the original's (found by its recording file) and recorded as a branch when
/// options.record is set.
int take_over_recording(const std::string& recording, const RunOptions& options, double at_s);

}  // namespace harbour::records
