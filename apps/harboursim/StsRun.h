#pragma once

#include <string>

namespace harbour::apps {

/// `harboursim run`: an exercise headless with the autopilot, progress lines and the evaluation.
struct RunOptions {
  std::string exercise;  ///< exercise file
  bool autopilot = false;
  std::string record;  ///< recording file to write ("" for none)
};
int run_exercise(const RunOptions& options);

/// `harboursim replay`: re-simulates a recording, checks every recorded second's hash, prints the evaluation.
int replay_recording(const std::string& recording, const std::string& exercise);

}  // namespace harbour::apps
