#pragma once

#include <string>

#include "harbour/records/Centre.h"

namespace harbour::apps {

/// `harboursim routes list|show|enrol|sign-off|retry`.
int list_routes(const records::CentreFolders& centre);
int show_route(const std::string& database, const records::CentreFolders& centre, const std::string& route_id,
               const std::string& trainee);
int enrol_trainee(const std::string& database, const records::CentreFolders& centre,
                  const std::string& trainee, const std::string& route_id);
/// An instructor's decision (sign_off or retry) on a stage, with its reason; audited.
int decide_stage(const std::string& database, const records::CentreFolders& centre,
                 const std::string& trainee, const std::string& route_id, const std::string& stage,
                 const std::string& action, const std::string& reason);

}  // namespace harbour::apps
