#pragma once

#include <string>

namespace harbour::apps {

/// `harboursim trainees add|list` and `harboursim results`.
int add_trainee(const std::string& database, const std::string& id, const std::string& name);
int list_trainees(const std::string& database);
int list_results(const std::string& database, const std::string& trainee);

}  // namespace harbour::apps
