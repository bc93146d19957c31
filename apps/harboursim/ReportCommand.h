#pragma once

#include <string>

#include "harbour/records/Centre.h"

namespace harbour::apps {

/// `harboursim report trainee ID` / `harboursim report class`: writes the report to `out` (a .pdf, or the
/// page itself for a .html).
int write_report(const std::string& database, const records::CentreFolders& centre,
                 const std::string& trainee, const std::string& out);

}  // namespace harbour::apps
