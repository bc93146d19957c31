#include "TraineesCommand.h"

#include <cstdio>
#include <optional>
#include <string>

#include "harbour/core/Text.h"
#include "harbour/records/Centre.h"
#include "harbour/records/RecordsStore.h"

namespace harbour::apps {

int add_trainee(const std::string& database, const std::string& id, const std::string& name) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  db.add_trainee(id, name);
  std::printf("trainee %s (%s) added\n", id.c_str(), name.c_str());
  return 0;
}

int list_trainees(const std::string& database) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  for (const records::TraineeRow& t : db.trainees())
    std::printf("%-16s %s\n", core::printable(t.id).c_str(), core::printable(t.name).c_str());
  return 0;
}

int list_results(const std::string& database, const std::string& trainee) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  const auto attempts = db.attempts(trainee.empty() ? std::nullopt : std::optional(trainee));
  std::printf("%-8s %-16s %-9s %-12s %-20s %-11s %6s %6s  %s\n", "attempt", "started (UTC)", "by", "trainee",
              "exercise", "status", "moves", "score", "from");
  for (const records::AttemptRow& a : attempts) {
    const std::string score =
        a.score ? std::to_string(static_cast<int>(*a.score)) + (a.passed ? " P" : " F") : "-";
    const std::string from =
        a.parent ? "take-over of " + std::to_string(*a.parent) + " at step " + std::to_string(a.branch_step)
                 : "";
    std::string started = a.started_at.empty() ? "-" : a.started_at.substr(0, 16);  // to the minute
    if (started.size() > 10 && started[10] == 'T') started[10] = ' ';
    std::printf("%-8lld %-16s %-9s %-12s %-20s %-11s %6d %6s  %s\n", static_cast<long long>(a.id),
                core::printable(started).c_str(), a.autopilot ? "autopilot" : "trainee",
                core::printable(a.trainee).c_str(), core::printable(a.exercise).c_str(),
                core::printable(a.status).c_str(), a.moves, score.c_str(), from.c_str());
  }
  return 0;
}

}  // namespace harbour::apps
