#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harbour/records/RecordsStore.h"
#include "harbour/training/Report.h"

namespace harbour::records {

/// A trainee's routes (those of `routes` they are enrolled in) and their progress on each.
std::vector<training::RouteStanding> route_standings(RecordsStore& db,
                                                     const std::vector<training::Route>& routes,
                                                     const std::string& trainee);

/// What a trainee's report holds, read from the records; throws std::out_of_range for an unknown trainee.
training::TraineeReportData trainee_report_data(RecordsStore& db, const std::vector<training::Route>& routes,
                                                const std::string& trainee);
/// What the class report holds: every trainee in the records.
training::ClassReportData class_report_data(RecordsStore& db, const std::vector<training::Route>& routes);

/// Prints an HTML page to a PDF file with Debian's chromium, headless, in a private profile;
/// the page is written next to the PDF's temporary and both are replaced only when chromium succeeded, so
/// a failed print leaves no half-written PDF. Throws std::runtime_error with chromium's last words when it
/// fails or takes longer than 60 s.
void print_pdf(const std::string& html, const std::filesystem::path& pdf);

}  // namespace harbour::records
