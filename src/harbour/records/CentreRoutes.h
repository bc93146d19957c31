#pragma once

#include <string>
#include <vector>

#include "harbour/records/Centre.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/training/Route.h"

namespace harbour::records {

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
RouteStage next_route_stage(RecordsStore& db, const CentreFolders& centre, const std::string& trainee,
                            const std::string& route_id);

}  // namespace harbour::records
