#include "harbour/training/Cohort.h"

#include <algorithm>
#include <set>
#include <string_view>
#include <tuple>

#include "harbour/training/Figures.h"
#include "harbour/training/Route.h"

namespace harbour::training {

namespace {

bool counts(const AttemptFigures& a) {
  return a.status == "finished" && a.score.has_value();
}

using VersionKey = std::pair<std::string, std::string>;  // exercise, version

// The order figures are shown in: the figure table's (the score, the skills, the task, ...), then by name.
struct FigureOrder {
  bool operator()(const std::string& a, const std::string& b) const {
    return std::make_pair(figure_order(a), std::string_view(a)) <
           std::make_pair(figure_order(b), std::string_view(b));
  }
};

// Per exercise version, per figure, per trainee: the best value (by the figure's direction).
using Bests = std::map<VersionKey, std::map<std::string, std::map<std::string, double>, FigureOrder>>;

Bests bests_of(const std::vector<AttemptFigures>& attempts) {
  Bests bests;
  for (const AttemptFigures& a : attempts) {
    if (!counts(a)) continue;
    auto& by_figure = bests[{a.exercise, a.exercise_version}];
    for (const auto& [figure, value] : figures_of(a)) {
      auto [it, added] = by_figure[figure].try_emplace(a.trainee, value);
      if (!added)
        it->second = higher_is_better(figure) ? std::max(it->second, value) : std::min(it->second, value);
    }
  }
  return bests;
}

std::optional<double> mean(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  double sum = 0.0;
  for (double v : values)
    sum += v;
  return sum / static_cast<double>(values.size());
}

}  // namespace

bool higher_is_better(const std::string& figure) {
  return figure_words(figure).higher_better;
}

std::vector<std::pair<std::string, double>> figures_of(const AttemptFigures& attempt) {
  std::vector<std::pair<std::string, double>> figures;
  if (attempt.score) figures.emplace_back("score", *attempt.score);
  figures.insert(figures.end(), attempt.metrics.begin(), attempt.metrics.end());
  return figures;
}

std::string place_words(int place, int of, int tied) {
  const int last_two = place % 100, last = place % 10;
  const char* suffix = last_two >= 11 && last_two <= 13 ? "th"
                       : last == 1                      ? "st"
                       : last == 2                      ? "nd"
                       : last == 3                      ? "rd"
                                                        : "th";
  return std::to_string(place) + suffix + " of " + std::to_string(of) + (tied > 0 ? " (tied)" : "");
}

std::vector<Standing> standings(const std::vector<AttemptFigures>& attempts, const std::string& trainee) {
  std::vector<Standing> out;
  for (const auto& [version, by_figure] : bests_of(attempts)) {
    for (const auto& [figure, by_trainee] : by_figure) {
      const auto own = by_trainee.find(trainee);
      if (own == by_trainee.end()) continue;
      const bool higher = higher_is_better(figure);
      std::vector<double> ranked;  // better is larger
      for (const auto& [who, best] : by_trainee)
        ranked.push_back(higher ? best : -best);
      const double mine = higher ? own->second : -own->second;
      Standing standing{version.first,
                        version.second,
                        figure,
                        higher,
                        own->second,
                        static_cast<int>(by_trainee.size()),
                        percentile_rank(ranked, mine)};
      for (const double other : ranked) {
        standing.place += other > mine ? 1 : 0;
        standing.tied += other == mine ? 1 : 0;
      }
      standing.tied -= 1;  // the trainee's own
      out.push_back(standing);
    }
  }
  return out;
}

std::vector<TraineeSummary> class_overview(const std::vector<AttemptFigures>& attempts,
                                           const std::vector<std::string>& trainees) {
  std::vector<TraineeSummary> out;
  static const char* const skill_names[3] = {"skill_safety", "skill_precision", "skill_productivity"};
  for (const std::string& trainee : trainees) {
    TraineeSummary s;
    s.trainee = trainee;
    std::vector<const AttemptFigures*> finished;
    for (const AttemptFigures& a : attempts) {
      if (a.trainee != trainee) continue;
      ++s.attempts;
      if (!counts(a)) continue;
      finished.push_back(&a);
      s.passed += a.passed ? 1 : 0;
      s.best_score = std::max(s.best_score.value_or(*a.score), *a.score);
    }
    s.finished = static_cast<int>(finished.size());
    if (!finished.empty()) {
      s.first_score = finished.front()->score;
      s.last_score = finished.back()->score;
    }
    const std::size_t recent_from = finished.size() > 3 ? finished.size() - 3 : 0;
    std::vector<double> recent;
    std::array<std::vector<double>, 3> recent_skill;
    for (std::size_t i = recent_from; i < finished.size(); ++i) {
      recent.push_back(*finished[i]->score);
      for (int k = 0; k < 3; ++k) {
        const auto found = finished[i]->metrics.find(skill_names[k]);
        if (found != finished[i]->metrics.end()) recent_skill[k].push_back(found->second);
      }
    }
    s.recent_score = mean(recent);
    for (int k = 0; k < 3; ++k)
      s.recent_skills[k] = mean(recent_skill[k]);
    if (finished.size() >= 2) {
      // least squares of score on the attempt's index 0..n-1
      const double n = static_cast<double>(finished.size());
      const double x_mean = (n - 1.0) / 2.0;
      double y_sum = 0.0;
      for (const AttemptFigures* a : finished)
        y_sum += *a->score;
      const double y_mean = y_sum / n;
      double sxy = 0.0, sxx = 0.0;
      for (std::size_t i = 0; i < finished.size(); ++i) {
        const double dx = static_cast<double>(i) - x_mean;
        sxy += dx * (*finished[i]->score - y_mean);
        sxx += dx * dx;
      }
      s.trend = sxy / sxx;
    }
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<Compared> compare(const std::vector<AttemptFigures>& attempts, const std::string& first,
                              const std::string& second) {
  std::vector<Compared> out;
  for (const auto& [version, by_figure] : bests_of(attempts)) {
    for (const auto& [figure, by_trainee] : by_figure) {
      const auto a = by_trainee.find(first), b = by_trainee.find(second);
      if (a == by_trainee.end() && b == by_trainee.end()) continue;
      out.push_back({version.first, version.second, figure, higher_is_better(figure),
                     a == by_trainee.end() ? std::nullopt : std::optional(a->second),
                     b == by_trainee.end() ? std::nullopt : std::optional(b->second)});
    }
  }
  return out;
}

}  // namespace harbour::training
