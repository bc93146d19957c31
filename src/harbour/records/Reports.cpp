#include "harbour/records/Reports.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "harbour/core/Text.h"
#include "harbour/io/RouteFiles.h"

extern char** environ;

namespace harbour::records {
namespace {

// The current time in UTC as a report prints it ("2026-11-25 09:30 UTC").
std::string report_time_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
  return text;
}

}  // namespace

std::vector<training::RouteStanding> route_standings(RecordsStore& db,
                                                     const std::vector<training::Route>& routes,
                                                     const std::string& trainee) {
  std::vector<training::RouteStanding> out;
  for (const EnrolmentRow& e : db.enrolments(trainee)) {
    for (const training::Route& r : routes)
      if (r.id == e.route)
        out.push_back(
            {r, training::progress(r, db.stage_attempts(trainee, r.id), db.overrides(trainee, r.id))});
  }
  return out;
}

training::TraineeReportData trainee_report_data(RecordsStore& db, const std::vector<training::Route>& routes,
                                                const std::string& trainee) {
  training::TraineeReportData d;
  for (const TraineeRow& t : db.trainees())
    if (t.id == trainee) d.name = t.name;
  if (!db.has_trainee(trainee)) throw std::out_of_range("no trainee '" + core::printable(trainee) + "'");
  d.trainee = trainee;
  d.generated_at = report_time_now();
  const std::vector<training::AttemptFigures> all = db.attempt_figures();
  for (const training::AttemptFigures& a : all)
    if (a.trainee == trainee) d.attempts.push_back(a);
  d.standings = training::standings(all, trainee);
  d.routes = route_standings(db, routes, trainee);
  return d;
}

training::ClassReportData class_report_data(RecordsStore& db, const std::vector<training::Route>& routes) {
  training::ClassReportData d;
  d.generated_at = report_time_now();
  std::vector<std::string> ids;
  for (const TraineeRow& t : db.trainees()) {
    ids.push_back(t.id);
    d.names.push_back(t.name);
    d.routes.push_back(route_standings(db, routes, t.id));
  }
  d.lines = training::class_overview(db.attempt_figures(), ids);
  return d;
}

namespace {

std::string tail_of(const std::filesystem::path& file, std::size_t bytes) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  return s.size() > bytes ? s.substr(s.size() - bytes) : s;
}

}  // namespace

void print_pdf(const std::string& html, const std::filesystem::path& pdf) {
  namespace fs = std::filesystem;
  char pattern[] = "/tmp/harboursim-report-XXXXXX";
  if (!mkdtemp(pattern)) throw std::runtime_error("printing a report: cannot make a temporary folder");
  const fs::path work = pattern;
  struct Cleanup {
    fs::path path;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } cleanup{work};
  const fs::path page = work / "report.html", printed = work / "report.pdf", log = work / "chromium.log";
  {
    std::ofstream out(page, std::ios::binary);
    out << html;
    if (!out) throw std::runtime_error("printing a report: cannot write " + page.string());
  }
  const std::string profile = "--user-data-dir=" + (work / "profile").string();
  const std::string target = "--print-to-pdf=" + printed.string();
  const std::string url = "file://" + page.string();
  std::vector<std::string> args = {"chromium",       "--headless",
                                   "--no-sandbox",  // our own page (no script, text escaped); root can't
                                   "--disable-gpu",  "--no-pdf-header-footer",
                                   "--no-first-run", profile,
                                   target,           url};
  std::vector<char*> argv;
  for (std::string& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "chromium", &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0)
    throw std::runtime_error("printing a report: cannot start chromium (apt install chromium): " +
                             std::string(std::strerror(spawned)));
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      throw std::runtime_error("printing a report: chromium took more than 60 s");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::error_code ec;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || fs::file_size(printed, ec) == 0 || ec)
    throw std::runtime_error("printing a report: chromium failed: " + tail_of(log, 600));
  // next to the target, then renamed over it: a reader never sees half a PDF
  const fs::path partial = pdf.string() + ".partial";
  fs::copy_file(printed, partial, fs::copy_options::overwrite_existing, ec);
  if (!ec) fs::rename(partial, pdf, ec);
  if (ec) {
    fs::remove(partial, ec);
    throw std::runtime_error("printing a report: cannot write " + pdf.string() + ": " + ec.message());
  }
}

}  // namespace harbour::records
