#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace harbour::training {

/// A bound on one stored metric of an attempt (its name as the records store it: sim::Metrics::rows() and
/// skill_safety, skill_precision, skill_productivity).
struct MetricBound {
  std::string metric;
  std::optional<double> min, max;
};

/// One stage of a training route: an exercise to pass `repetitions` times, each passing attempt meeting the
/// score and every metric bound, after the stages it requires. After `max_attempts` attempts without
/// enough passes the stage is blocked until an instructor signs it off or grants another round.
struct Stage {
  std::string id;                   ///< unique in its route
  std::string goal;                 ///< the training goal it belongs to ("Controls and a single lift")
  std::string exercise;             ///< as the route names it: a shipped exercise's name, or a path
  std::string exercise_file;        ///< the file it names
  std::optional<double> min_score;  ///< unset: the exercise's own pass mark (Score::passed)
  std::vector<MetricBound> bounds;
  int repetitions = 1;
  int max_attempts = 5;
  std::vector<std::string> requires_stages;
};

/// A training route (data/routes/*.yaml): stages in order, grouped by training goal.
struct Route {
  std::string id;  ///< the file's stem
  std::string name;
  std::string machine;  ///< what it trains on (informative: "STS")
  std::vector<Stage> stages;
  const Stage* stage(const std::string& stage_id) const;
};

/// A stored attempt of a trainee at a route's stage, as progress needs it.
struct StageAttempt {
  std::string stage;
  std::string status;  ///< running, finished, interrupted, diverged
  std::optional<double> score;
  bool passed = false;  ///< the exercise's own pass mark
  std::map<std::string, double> metrics;
};

/// An instructor's decision on a stage, stored with its reason: "sign_off" counts the stage as passed;
/// "retry" grants another round of max_attempts to a blocked stage.
struct Override {
  std::string stage, action, reason, account, at;
};

enum class StageState { kLocked, kOpen, kPassed, kBlocked };
const char* state_name(StageState state);

/// Where a trainee stands on one stage.
struct StageProgress {
  std::string stage;
  StageState state = StageState::kLocked;
  int attempts = 0;  ///< attempts that count (finished or interrupted; a diverged one is the physics')
  int passes = 0;    ///< of them, those meeting the stage's criteria
  int attempts_allowed = 0;  ///< max_attempts times (1 + retries granted)
  bool signed_off = false;
  std::optional<double> best_score;
  std::vector<std::string> missing;  ///< for a locked stage: the required stages not yet passed
};

struct RouteProgress {
  std::vector<StageProgress> stages;  ///< in the route's order
  /// The stage the station offers next: the first open one in order; nullopt when every stage is passed or
  /// the open ones are all blocked.
  std::optional<std::string> next;
  bool complete = false;  ///< every stage passed
};

/// Whether one attempt meets a stage's criteria; `why` says the first it misses.
bool meets(const Stage& stage, const StageAttempt& attempt, std::string* why = nullptr);

/// A trainee's progress on a route from their attempts at its stages (any order) and the instructor's
/// overrides: a pure function of what the records hold.
RouteProgress progress(const Route& route, const std::vector<StageAttempt>& attempts,
                       const std::vector<Override>& overrides);

/// Where `value` stands in `cohort` (the value included or not): the percentile rank, 100 x (values below
/// + half the values equal) / count, in [0, 100]; 100 for an empty cohort.
double percentile_rank(const std::vector<double>& cohort, double value);

}  // namespace harbour::training
