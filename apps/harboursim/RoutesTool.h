#pragma once

#include <string>

#include "harbour/io/RecordsStore.h"
#include "harbour/training/Route.h"

namespace harbour::apps {

/// The shipped routes (data/routes) with their exercises (data/exercises).
training::Route load_shipped_route(const std::string& id);

/// The stage a trainee enrolled in `route_id` is to run next, with its exercise file; throws naming why
/// there is none (not enrolled, route complete, the open stages blocked until an instructor decides).
struct RouteStage {
  training::Route route;
  training::Stage stage;
};
RouteStage next_route_stage(io::RecordsStore& db, const std::string& trainee, const std::string& route_id);

/// `harboursim routes list|show|enrol|sign-off|retry`.
int list_routes();
int show_route(const std::string& database, const std::string& route_id, const std::string& trainee);
int enrol_trainee(const std::string& database, const std::string& trainee, const std::string& route_id);
/// An instructor's decision (sign_off or retry) on a stage, with its reason; audited.
int decide_stage(const std::string& database, const std::string& trainee, const std::string& route_id,
                 const std::string& stage, const std::string& action, const std::string& reason);

}  // namespace harbour::apps
