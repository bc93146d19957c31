#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "harbour/io/RecordingFile.h"
#include "harbour/io/RecordsStore.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Recording.h"
#include "harbour/station/RealTimeLoop.h"

namespace harbour::station {

/// An instructor's take-over: the attempt continues a stored one live from a moment of its recording (a new
/// attempt, branched from the recorded one).
struct TakeOverFrom {
  std::string recording;  ///< the recording file
  std::int64_t step = 0;  ///< where the new attempt begins
};

struct SessionOptions {
  std::string trainee;   ///< stored under this trainee (must exist)
  std::string record;    ///< recording file ("" for none)
  std::string database;  ///< records connection
  LoopSettings loop;
  std::optional<TakeOverFrom> take_over;
  std::string route, stage;      ///< the training route stage it runs ("" : none)
  std::string exercise_version;  ///< io::exercise_version of its file
};

/// How a session ended.
struct SessionResult {
  std::string status;  ///< finished, interrupted, diverged (as stored)
  std::int64_t attempt = 0;
  sim::Metrics metrics;
  sim::Score score;
  LoopStats loop;
  std::int64_t hash_mismatches = 0;  ///< live checkpoints the recorder's shadow did not reproduce (0)
};

/// One trainee's live attempt at an exercise: the simulation on the real-time loop, and on a thread of its
/// own the record keeper, which re-steps a shadow of the simulation with every step's controls and commands
/// (determinism makes it the same state) to evaluate, record (checkpoints, keyframes, the streamed file) and
/// store the attempt's progress in the database, all off the step thread.
class Session {
 public:
  /// Opens the database and the recording and begins the attempt; throws naming what failed. With a
  /// take-over the simulation is the recorded one at that step (re-simulated: the evaluation sees what the
  /// first attempt did), the recording continues the original's prefix and the attempt names its parent.
  Session(const sim::ExerciseSettings& exercise, const SessionOptions& options);
  ~Session();

  sim::Simulation& simulation() { return *simulation_; }
  RealTimeLoop& loop() { return *loop_; }
  std::int64_t attempt() const { return attempt_; }
  /// The moves the evaluation counted before the loop started (a take-over's: the pilot resumes after them).
  int moves_before_start() const { return moves_before_start_; }
  /// Starts the loop and the record keeper.
  void start();
  /// Whether the exercise is over (its moves done, past its time and overtime, or diverged).
  bool over() const { return over_.load(); }
  /// The evaluation so far (the keeper's copy, refreshed every 50 steps and at each move).
  sim::Metrics metrics() const;
  /// The score on the figures so far (refreshed with them).
  sim::Score score() const;
  /// Something the station saw (an input device lost or back): stored with the attempt's events at the
  /// simulated time the keeper has reached (any thread).
  void note_event(const std::string& kind, double value = 0.0);
  /// Stops the loop (if still running), lets the keeper catch up, closes the recording and stores the
  /// attempt: `interrupted` when the trainee or a signal stopped it before the end.
  SessionResult finish(bool interrupted);

 private:
  void keep();
  void keep(const StepRecord& record);

  sim::ExerciseSettings exercise_;
  SessionOptions options_;
  std::unique_ptr<sim::Simulation> simulation_, shadow_;
  std::unique_ptr<RealTimeLoop> loop_;
  sim::Evaluator evaluator_;
  sim::Recorder recorder_;
  std::optional<io::RecordingWriter> writer_;
  std::unique_ptr<io::RecordsStore> db_;
  std::int64_t attempt_ = 0;
  std::thread keeper_;
  std::atomic<bool> over_{false}, loop_done_{false};
  std::atomic<std::int64_t> hash_mismatches_{0};
  mutable std::mutex metrics_mutex_;
  sim::Metrics metrics_;
  sim::Score score_;
  std::string keeper_error_;
  std::mutex notes_mutex_;
  std::vector<std::pair<std::string, double>> notes_;
  void store_notes();
  bool finished_ = false;
  int moves_before_start_ = 0;
};

}  // namespace harbour::station
