#include "ReportCommand.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "harbour/records/CentreRoutes.h"
#include "harbour/records/Reports.h"

namespace harbour::apps {

int write_report(const std::string& database, const records::CentreFolders& centre,
                 const std::string& trainee, const std::string& out) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  const std::vector<training::Route> routes = records::load_centre_routes(centre);
  std::string html;
  try {
    html = trainee.empty() ? training::class_report_html(records::class_report_data(db, routes))
                           : training::trainee_report_html(records::trainee_report_data(db, routes, trainee));
  } catch (const std::out_of_range& e) {
    std::fprintf(stderr, "harboursim: %s\n", e.what());
    return 1;
  }
  const std::filesystem::path path = out;
  if (path.extension() == ".html") {
    const std::filesystem::path partial = out + ".partial";
    {
      std::ofstream file(partial, std::ios::binary);
      file << html;
      if (!file) throw std::runtime_error("cannot write " + partial.string());
    }
    std::filesystem::rename(partial, path);
  } else if (path.extension() == ".pdf") {
    records::print_pdf(html, path);
  } else {
    std::fprintf(stderr, "harboursim: report --out %s: a .pdf or .html file\n", out.c_str());
    return 2;
  }
  std::printf("%s report written to %s\n", trainee.empty() ? "class" : ("trainee " + trainee + "'s").c_str(),
              out.c_str());
  return 0;
}

}  // namespace harbour::apps
