#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "harbour/io/RecordingFile.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Recording.h"
#include "harbour/station/RealTimeLoop.h"
#include "harbour/station/SpscRing.h"

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
  std::string route, stage;   ///< the training route stage it runs ("" : none)
  io::ExerciseSource source;  ///< the exercise as it runs (kept in the records by its version)
  bool autopilot = false;     ///< the scripted operator drives (stored with the attempt)
};

/// How a live attempt came to its end.
enum class SessionEnd : std::uint8_t {
  kRan,                  ///< the exercise ended it (its goals met, its time and overtime past)
  kInterrupted,          ///< the station stopped first (a signal, its window closed, its run's time up)
  kStoppedByInstructor,  ///< the instructor stopped or reset it
};

struct SessionResult {
  std::string status;  ///< as stored (records::attempt_status)
  std::int64_t attempt = 0;
  sim::Metrics metrics;
  sim::Score score;
  LoopStats loop;
};

/// One trainee's live attempt at an exercise: the simulation on the real-time loop, evaluated on the step
/// thread right after each step, and on a thread of its own the record keeper, which records what the step
/// thread hands on (controls, commands, checkpoints, keyframes: the streamed file) and stores the attempt's
/// progress in the database as it grows, both off the step thread.
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
  /// The controls standing where a take-over began.
  const scene::Controls& levers_before_start() const { return levers_before_start_; }
  /// Starts the loop and the record keeper.
  void start();
  /// Whether the exercise is over (its moves done, past its time and overtime, or diverged).
  bool over() const { return over_.load(); }
  /// The evaluation so far (a copy, refreshed every 50 steps and whenever a move or an event is counted).
  sim::Metrics metrics() const;
  /// The score on the figures so far (refreshed with them).
  sim::Score score() const;
  /// Something the station saw (an input device lost or back): stored with the attempt's events at the
  /// simulated time the record keeper has reached (any thread).
  void note_event(const std::string& kind, double value = 0.0);
  /// Stops the loop (if still running), lets the keeper catch up, closes the recording and stores the
  /// attempt: `interrupted` when the trainee or a signal stopped it before the end.
  SessionResult finish(SessionEnd end);
  /// A team session's member: what its station measured of the team, stored with the attempt's figures.
  /// Before finish().
  void set_team_figures(const sim::TeamFigures& figures) { team_ = figures; }
  /// The attempt was a team session's member: stored with it (records::AttemptRow::team, team_role,
  /// team_session).
  void set_team(const std::string& team, const std::string& role, const std::string& session) {
    team_member_ = {team, role, session};
  }

 private:
  /// The step thread's part: evaluates the step just taken, hands what grew to the keeper.
  void evaluate(const sim::Simulation& simulation, const scene::Controls& controls);
  void publish_metrics();
  void keep();
  /// One pass over what the step thread handed on; false when there was nothing.
  bool keep_what_is_handed();
  void keep(const StepRecord& record);

  sim::ExerciseSettings exercise_;
  SessionOptions options_;
  std::unique_ptr<sim::Simulation> simulation_;
  std::unique_ptr<RealTimeLoop> loop_;
  sim::Evaluator evaluator_;  // the step thread's, once the loop has started
  sim::Progress handed_;      // the step thread's: the progress last handed to the keeper
  SpscRing<sim::Progress> progress_{1 << 12};
  sim::Progress stored_;                     // the keeper's: what the records hold
  std::atomic<std::int64_t> kept_steps_{0};  // the keeper's: the steps it has recorded
  sim::Recorder recorder_;
  std::optional<io::RecordingWriter> writer_;
  std::unique_ptr<records::RecordsStore> db_;
  std::int64_t attempt_ = 0;
  std::thread keeper_;
  std::atomic<bool> over_{false}, loop_done_{false};
  mutable std::mutex metrics_mutex_;
  sim::Metrics metrics_;  // published by the step thread
  bool goals_met_ = false;
  std::string keeper_error_;
  std::mutex notes_mutex_;
  std::vector<std::pair<std::string, double>> notes_;
  void store_notes();
  bool finished_ = false;
  std::optional<sim::TeamFigures> team_;
  std::array<std::string, 3> team_member_;  // team, role, session ("": alone)
  int moves_before_start_ = 0;
  scene::Controls levers_before_start_;
};

}  // namespace harbour::station
