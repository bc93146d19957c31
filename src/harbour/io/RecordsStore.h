#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harbour/sim/Evaluation.h"

namespace harbour::io {

/// A trainee in the records.
struct TraineeRow {
  std::string id;
  std::string name;
};

/// An exercise attempt in the records.
struct AttemptRow {
  std::int64_t id = 0;
  std::string trainee;
  std::string exercise;
  std::string status;  ///< running, finished
  std::optional<double> score;
  bool passed = false;
  std::optional<std::int64_t> parent;  ///< the attempt an instructor took over from
  std::int64_t branch_step = 0;
  std::string recording;
  int moves = 0;  ///< moves stored so far
};

/// The trainee database: trainees, attempts, moves and events as they happen, final metrics and score. One
/// interface over SOCI: "sqlite3://db=<file>" (the default: one file, WAL, waiting up to 10 s for another
/// writer's lock) or "postgresql://dbname=... host=..." for a training centre; the SQL is the portable subset
/// both accept. Every write commits at once, so a crash loses nothing already measured.
class RecordsStore {
 public:
  /// Opens (and creates the schema in) a database; throws std::runtime_error naming the connection on
  /// failure, or when a table of ours exists without the columns this build uses (nothing is written then).
  /// Every later error names the connection and what was being done; attempts() refuses a row whose status,
  /// pass flag, score or branch step no run of ours could have written, naming the attempt.
  explicit RecordsStore(const std::string& connection);
  ~RecordsStore();
  RecordsStore(const RecordsStore&) = delete;
  RecordsStore& operator=(const RecordsStore&) = delete;

  void add_trainee(const std::string& id, const std::string& name);
  std::vector<TraineeRow> trainees();
  bool has_trainee(const std::string& id);

  /// Starts an attempt and returns its id.
  std::int64_t begin_attempt(const std::string& trainee, const std::string& exercise,
                             std::optional<std::int64_t> parent = std::nullopt, std::int64_t branch_step = 0);
  void record_move(std::int64_t attempt, int index, double completed_at_s, double cycle_time_s);
  void record_event(std::int64_t attempt, double at_s, const std::string& kind, double value);
  void finish_attempt(std::int64_t attempt, const sim::Metrics& metrics, const sim::Score& score,
                      const std::string& recording);
  /// Attempts, newest first, optionally of one trainee.
  std::vector<AttemptRow> attempts(const std::optional<std::string>& trainee = std::nullopt);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace harbour::io
