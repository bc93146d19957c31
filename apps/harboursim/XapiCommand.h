#pragma once

#include <string>

#include "harbour/training/Xapi.h"

namespace harbour::apps {

/// `harboursim xapi status`: the outbox by state, and the errors of those failing.
int xapi_status(const std::string& database);
/// `harboursim xapi send`: one pass (exit 0: nothing due is left unsent, 3: some wait for a retry), or with
/// `watch` a pass every second until SIGINT/SIGTERM. The credentials are read from `credentials_file`.
int xapi_send(const std::string& database, const std::string& endpoint, const std::string& credentials_file,
              bool watch, const training::xapi::Centre& centre);

}  // namespace harbour::apps
