#include "RoutesTool.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "harbour/core/Text.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/records/CentreRoutes.h"

namespace harbour::apps {
namespace {

std::string criteria(const training::Stage& s) {
  char text[64];
  std::string out = s.min_score ? (std::snprintf(text, sizeof text, "score >= %g", *s.min_score), text)
                                : "the exercise's pass mark";
  for (const training::MetricBound& b : s.bounds) {
    if (b.min) out += (std::snprintf(text, sizeof text, ", %s >= %g", b.metric.c_str(), *b.min), text);
    if (b.max) out += (std::snprintf(text, sizeof text, ", %s <= %g", b.metric.c_str(), *b.max), text);
  }
  return out;
}

}  // namespace

int list_routes(const records::CentreFolders& centre) {
  for (const training::Route& r : records::load_centre_routes(centre)) {
    std::printf("%-16s %s (%s): ", r.id.c_str(), r.name.c_str(), r.machine.c_str());
    std::string last_goal;
    for (const training::Stage& s : r.stages) {
      if (s.goal != last_goal)
        std::printf("%s%s: ", last_goal.empty() ? "" : "; ", s.goal.c_str());
      else
        std::printf(", ");
      std::printf("%s", s.id.c_str());
      last_goal = s.goal;
    }
    std::printf("\n");
  }
  return 0;
}

int show_route(const std::string& database, const records::CentreFolders& centre, const std::string& route_id,
               const std::string& trainee) {
  const training::Route route = records::load_named_route(centre, route_id);
  std::optional<training::RouteProgress> p;
  if (!trainee.empty()) {
    records::RecordsStore db(database.empty() ? records::default_database() : database);
    if (!db.has_trainee(trainee)) throw std::runtime_error("no trainee '" + core::printable(trainee) + "'");
    p = training::progress(route, db.stage_attempts(trainee, route.id), db.overrides(trainee, route.id));
  }
  std::printf("route %s: %s (%s)%s\n", route.id.c_str(), route.name.c_str(), route.machine.c_str(),
              trainee.empty() ? "" : (", trainee " + trainee).c_str());
  std::string last_goal;
  for (std::size_t n = 0; n < route.stages.size(); ++n) {
    const training::Stage& s = route.stages[n];
    if (s.goal != last_goal) std::printf("  %s\n", s.goal.c_str());
    last_goal = s.goal;
    std::string requires_text;
    for (const std::string& r : s.requires_stages)
      requires_text += (requires_text.empty() ? "" : ", ") + r;
    std::printf("    %-18s %-26s %d of %d attempts pass: %s%s\n", s.id.c_str(), s.exercise.c_str(),
                s.repetitions, s.max_attempts, criteria(s).c_str(),
                requires_text.empty() ? "" : ("; after " + requires_text).c_str());
    if (!p) continue;
    const training::StageProgress& sp = p->stages[n];
    char best[32] = "-";
    if (sp.best_score) std::snprintf(best, sizeof best, "%.1f", *sp.best_score);
    std::printf("      %-8s %d/%d passes, %d/%d attempts, best %s%s%s\n", training::state_name(sp.state),
                sp.passes, s.repetitions, sp.attempts, sp.attempts_allowed, best,
                sp.signed_off ? ", signed off" : "", p->next == s.id ? "  <- next" : "");
  }
  if (p)
    std::printf("%s\n", p->complete ? "route complete"
                        : p->next   ? ""
                                    : "no stage open: an instructor decides");
  return 0;
}

int enrol_trainee(const std::string& database, const records::CentreFolders& centre,
                  const std::string& trainee, const std::string& route_id) {
  const training::Route route = records::load_named_route(centre, route_id);
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  const bool added = db.enrol(trainee, route.id, "(command line)");
  if (added) db.audit("(command line)", "enrol", trainee, route.id);
  std::printf("trainee %s %s route %s\n", trainee.c_str(), added ? "enrolled in" : "was already enrolled in",
              route.id.c_str());
  return 0;
}

int decide_stage(const std::string& database, const records::CentreFolders& centre,
                 const std::string& trainee, const std::string& route_id, const std::string& stage,
                 const std::string& action, const std::string& reason) {
  const training::Route route = records::load_named_route(centre, route_id);
  if (!route.stage(stage))
    throw std::runtime_error("route '" + route.id + "' has no stage '" + core::printable(stage) + "'");
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  db.add_override(trainee, route.id, {stage, action, reason, "(command line)", ""});
  db.audit("(command line)", action, trainee + " " + route.id + "/" + stage, reason);
  std::printf("%s: %s %s/%s (%s)\n", action.c_str(), trainee.c_str(), route.id.c_str(), stage.c_str(),
              reason.c_str());
  return 0;
}

}  // namespace harbour::apps
