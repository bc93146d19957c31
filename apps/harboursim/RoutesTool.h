#pragma once

#include <string>
#include <vector>

#include "Centre.h"

#include "harbour/records/RecordsStore.h"
#include "harbour/training/Route.h"

namespace harbour::apps {

/// The centre's routes and the shipped ones, their stages' exercises looked up in the centre's folder and
/// then the shipped one (io::load_routes).
std::vector<training::Route> load_centre_routes(const CentreFolders& centre);
/// One of them by name; throws naming those there are.
training::Route load_named_route(const CentreFolders& centre, const std::string& id);

/// The stage a trainee enrolled in `route_id` is to run next, with its exercise file; throws naming why
/// there is none (not enrolled, route complete, the open stages blocked until an instructor decides).
struct RouteStage {
  training::Route route;
  training::Stage stage;
};
RouteStage next_route_stage(records::RecordsStore& db, const CentreFolders& centre,
                            const std::string& trainee, const std::string& route_id);

/// `harboursim routes list|show|enrol|sign-off|retry`.
int list_routes(const CentreFolders& centre);
int show_route(const std::string& database, const CentreFolders& centre, const std::string& route_id,
               const std::string& trainee);
int enrol_trainee(const std::string& database, const CentreFolders& centre, const std::string& trainee,
                  const std::string& route_id);
/// An instructor's decision (sign_off or retry) on a stage, with its reason; audited.
int decide_stage(const std::string& database, const CentreFolders& centre, const std::string& trainee,
                 const std::string& route_id, const std::string& stage, const std::string& action,
                 const std::string& reason);

}  // namespace harbour::apps
