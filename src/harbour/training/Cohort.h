#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace harbour::training {

/// An attempt with its stored figures, as the cohort views need it.
struct AttemptFigures {
  std::int64_t id = 0;
  std::string trainee, exercise, exercise_version, route, stage;
  std::string status;  ///< running, finished, interrupted, diverged
  std::optional<double> score;
  bool passed = false;
  std::map<std::string, double> metrics;  ///< by stored name (sim::Metrics::rows() and the skills)
};

/// Whether a larger value of a figure is the better one, as the figure table says (training/Figures.h):
/// the score, the skills, work done and throughput; every other figure counts something to avoid.
bool higher_is_better(const std::string& figure);

/// The figures a view shows of an attempt: "score" and then its metrics by name.
std::vector<std::pair<std::string, double>> figures_of(const AttemptFigures& attempt);

/// A trainee's best on one figure of one exercise version, and where it stands among every trainee's best
/// there: the percentile rank (training::percentile_rank) with the better values ranked higher, so 100 is
/// ahead of everyone whatever the figure's direction.
struct Standing {
  std::string exercise, exercise_version, figure;
  bool higher_better = true;
  double best = 0.0;
  int trainees = 0;  ///< with a finished attempt at this version
  double percentile = 0.0;
  int place = 1;  ///< 1 + the trainees whose best is better
  int tied = 0;   ///< the other trainees whose best is the same
};

/// A place in words: "1st of 3", "2nd of 4 (tied)".
std::string place_words(int place, int of, int tied);

/// The trainee's standings on every figure of every exercise version they finished (finished attempts with
/// a score only), by exercise and version, then the score, the skills and the other figures by name.
std::vector<Standing> standings(const std::vector<AttemptFigures>& attempts, const std::string& trainee);

/// One trainee's line in a class overview.
struct TraineeSummary {
  std::string trainee;
  int attempts = 0;  ///< every attempt, whatever became of it
  int finished = 0;  ///< with a score
  int passed = 0;
  std::optional<double> first_score, last_score, best_score;
  std::optional<double> recent_score;                  ///< mean of the last three finished
  std::array<std::optional<double>, 3> recent_skills;  ///< safety, precision, productivity: same mean
  /// [points per attempt] the least-squares slope of the score over the finished attempts (two or more)
  std::optional<double> trend;
};

/// A line per trainee in `trainees` (in that order) from the attempts given in time order.
std::vector<TraineeSummary> class_overview(const std::vector<AttemptFigures>& attempts,
                                           const std::vector<std::string>& trainees);

/// Two trainees side by side on one figure of one exercise version: each one's best (unset: they have no
/// finished attempt there).
struct Compared {
  std::string exercise, exercise_version, figure;
  bool higher_better = true;
  std::optional<double> first, second;
};

/// Every figure of every exercise version either trainee finished, in the order of standings().
std::vector<Compared> compare(const std::vector<AttemptFigures>& attempts, const std::string& first,
                              const std::string& second);

}  // namespace harbour::training
