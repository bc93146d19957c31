#include "harbour/records/CentreRoutes.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "harbour/core/Text.h"
#include "harbour/io/RouteFiles.h"

namespace harbour::records {

std::vector<training::Route> load_centre_routes(const CentreFolders& centre) {
  return io::load_routes(centre.route_folders(), centre.exercise_folders());
}

training::Route load_named_route(const CentreFolders& centre, const std::string& id) {
  if (const std::string why = core::why_bad_name(id, 64); !why.empty() || id.find('/') != std::string::npos)
    throw std::runtime_error("route '" + core::printable(id, 64) +
                             "': a route's name, as harboursim routes list shows");
  for (const std::string& folder : centre.route_folders()) {
    const std::string file = folder + "/" + id + ".yaml";
    if (std::filesystem::is_regular_file(file)) return io::load_route(file, centre.exercise_folders());
  }
  std::string known;
  for (const training::Route& r : load_centre_routes(centre))
    known += (known.empty() ? "" : ", ") + r.id;
  throw std::runtime_error("no route '" + id + "' (there are: " + known + ")");
}

RouteStage next_route_stage(RecordsStore& db, const CentreFolders& centre, const std::string& trainee,
                            const std::string& route_id) {
  const training::Route route = load_named_route(centre, route_id);
  const auto enrolled = db.enrolments(trainee);
  if (std::none_of(enrolled.begin(), enrolled.end(),
                   [&](const EnrolmentRow& e) { return e.route == route.id; }))
    throw std::runtime_error("trainee '" + trainee + "' is not enrolled in route '" + route.id +
                             "' (harboursim routes enrol " + trainee + " " + route.id + ")");
  const training::RouteProgress p =
      training::progress(route, db.stage_attempts(trainee, route.id), db.overrides(trainee, route.id));
  if (p.complete)
    throw std::runtime_error("trainee '" + trainee + "' has passed every stage of route '" + route.id + "'");
  if (!p.next) {
    std::string blocked;
    for (const training::StageProgress& s : p.stages)
      if (s.state == training::StageState::kBlocked) blocked += (blocked.empty() ? "" : ", ") + s.stage;
    throw std::runtime_error("route '" + route.id + "': no stage open for '" + trainee +
                             "'; blocked after their attempts: " + blocked +
                             " (an instructor decides: harboursim routes sign-off|retry)");
  }
  return {route, *route.stage(*p.next)};
}

}  // namespace harbour::records
