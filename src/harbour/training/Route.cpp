#include "harbour/training/Route.h"

#include <algorithm>
#include <cstdio>
#include <functional>

namespace harbour::training {

const Stage* Route::stage(const std::string& stage_id) const {
  for (const Stage& s : stages)
    if (s.id == stage_id) return &s;
  return nullptr;
}

const char* state_name(StageState state) {
  switch (state) {
    case StageState::kLocked:
      return "locked";
    case StageState::kOpen:
      return "open";
    case StageState::kPassed:
      return "passed";
    case StageState::kBlocked:
      return "blocked";
  }
  return "?";
}

namespace {

std::string figure(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

bool meets(const Stage& stage, const StageAttempt& attempt, std::string* why) {
  const auto miss = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (attempt.status != "finished") return miss("not finished (" + attempt.status + ")");
  if (stage.min_score) {
    if (!attempt.score || *attempt.score < *stage.min_score)
      return miss("score " + (attempt.score ? figure(*attempt.score) : std::string("none")) + " under " +
                  figure(*stage.min_score));
  } else if (!attempt.passed) {
    return miss("the exercise's pass mark not reached");
  }
  for (const MetricBound& b : stage.bounds) {
    const auto found = attempt.metrics.find(b.metric);
    if (found == attempt.metrics.end()) return miss(b.metric + " not measured");
    if (b.min && found->second < *b.min)
      return miss(b.metric + " " + figure(found->second) + " under " + figure(*b.min));
    if (b.max && found->second > *b.max)
      return miss(b.metric + " " + figure(found->second) + " over " + figure(*b.max));
  }
  if (why) why->clear();
  return true;
}

RouteProgress progress(const Route& route, const std::vector<StageAttempt>& attempts,
                       const std::vector<Override>& overrides) {
  RouteProgress out;
  std::map<std::string, StageProgress> by_id;
  for (const Stage& stage : route.stages) {
    StageProgress p;
    p.stage = stage.id;
    int retries = 0;
    for (const Override& o : overrides) {
      if (o.stage != stage.id) continue;
      p.signed_off = p.signed_off || o.action == "sign_off";
      retries += o.action == "retry" ? 1 : 0;
    }
    p.attempts_allowed = stage.max_attempts * (1 + retries);
    for (const StageAttempt& a : attempts) {
      if (a.stage != stage.id || (a.status != "finished" && a.status != "interrupted")) continue;
      ++p.attempts;
      if (a.score) p.best_score = std::max(p.best_score.value_or(*a.score), *a.score);
      p.passes += meets(stage, a) ? 1 : 0;
    }
    by_id[stage.id] = p;
  }
  // states in prerequisite order (the loader refuses cycles; a stage being settled counts as not passed)
  std::map<std::string, bool> settling;
  const std::function<void(const Stage&)> settle = [&](const Stage& stage) {
    StageProgress& p = by_id[stage.id];
    if (settling.count(stage.id)) return;
    settling[stage.id] = true;
    for (const std::string& required : stage.requires_stages) {
      if (const Stage* r = route.stage(required)) settle(*r);
      if (by_id[required].state != StageState::kPassed) p.missing.push_back(required);
    }
    if (p.signed_off || p.passes >= stage.repetitions)
      p.state = StageState::kPassed;
    else if (!p.missing.empty())
      p.state = StageState::kLocked;
    else if (p.attempts >= p.attempts_allowed)
      p.state = StageState::kBlocked;
    else
      p.state = StageState::kOpen;
  };
  for (const Stage& stage : route.stages) {
    settle(stage);
    out.stages.push_back(by_id[stage.id]);
    if (out.stages.back().state == StageState::kOpen && !out.next) out.next = stage.id;
  }
  out.complete = std::all_of(out.stages.begin(), out.stages.end(),
                             [](const StageProgress& p) { return p.state == StageState::kPassed; });
  return out;
}

double percentile_rank(const std::vector<double>& cohort, double value) {
  if (cohort.empty()) return 100.0;
  double below = 0.0, equal = 0.0;
  for (double v : cohort) {
    below += v < value ? 1.0 : 0.0;
    equal += v == value ? 1.0 : 0.0;
  }
  return 100.0 * (below + 0.5 * equal) / static_cast<double>(cohort.size());
}

}  // namespace harbour::training
