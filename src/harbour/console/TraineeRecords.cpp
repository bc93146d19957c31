// The console's trainee records: trainees, attempts (and as CSV), a trainee's evolution and progress on the
// routes, enrolments and decisions, the class overview, comparisons and reports.
#include "harbour/console/ConsoleServer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/core/Text.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/io/TeamFiles.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/records/Reports.h"
#include "harbour/sim/MachineType.h"
#include "harbour/training/Figures.h"

namespace harbour::console {

std::optional<Console::Response> Console::trainees(Call& c) {
  json list = json::array();
  for (const records::TraineeRow& t : db_.trainees())
    list.push_back({{"id", t.id}, {"name", t.name}});
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::change_trainee(Call& c) {
  const auto& request = c.request;
  const bool adds = request.method() == http::verb::post;  // a new trainee; PATCH renames one
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  const std::optional<std::string> id = body ? text_field(*body, "id", 64, why) : std::nullopt;
  const std::optional<std::string> name = id ? text_field(*body, "name", 128, why) : std::nullopt;
  if (!name) return error(request, http::status::bad_request, why);
  try {
    if (adds)
      db_.add_trainee(*id, *name);
    else
      db_.rename_trainee(*id, *name);
  } catch (const std::out_of_range& e) {
    return error(request, http::status::not_found, e.what());
  } catch (const std::exception& e) {
    return error(request, http::status::bad_request, e.what());
  }
  audit_.add(c.account->name, adds ? "add_trainee" : "rename_trainee", *id, *name);
  return json_reply(request, adds ? http::status::created : http::status::ok, {{"id", *id}, {"name", *name}});
}

std::optional<Console::Response> Console::attempts(Call& c) {
  std::optional<std::string> trainee;
  if (!c.trainee.empty()) trainee = c.trainee;
  json list = json::array();
  for (const records::AttemptRow& a : db_.attempts(trainee))
    list.push_back({{"id", a.id},
                    {"trainee", a.trainee},
                    {"exercise", a.exercise},
                    {"status", a.status},
                    {"outcome", records::attempt_outcome(a)},
                    {"score", a.score ? json(*a.score) : json(nullptr)},
                    {"passed", a.passed},
                    {"moves", a.moves},
                    {"parent", a.parent ? json(*a.parent) : json(nullptr)},
                    {"route", a.route},
                    {"stage", a.stage},
                    {"exercise_version", a.exercise_version},
                    {"started_at", a.started_at},
                    {"ended_at", a.ended_at},
                    {"autopilot", a.autopilot},
                    {"team", a.team},
                    {"team_role", a.team_role},
                    {"team_session", a.team_session}});
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::attempt(Call& c) {
  const auto& request = c.request;
  const std::int64_t id = c.segment_id;
  const std::optional<records::AttemptRow> a = db_.attempt(id);
  if (!a || !owns(*c.account, a->trainee))
    return error(request, http::status::not_found, "no attempt " + std::to_string(id) + " for you");
  json events = json::array(), metrics = json::object(), figures = json::array(), deductions = json::array();
  for (const records::DeductionRow& d : db_.deductions(id))
    deductions.push_back(
        {{"reason", d.reason}, {"skill", d.skill}, {"count", d.count}, {"points", d.points}});
  for (const records::EventRow& e : db_.events(id))
    events.push_back(attempt_event_json(e.at_s, e.kind, e.value));
  std::vector<std::pair<std::string, double>> stored;
  for (const auto& [name, value] : db_.metrics(id)) {
    metrics[name] = value;
    stored.emplace_back(name, value);
  }
  // the figures in words, in the figure table's order
  std::stable_sort(stored.begin(), stored.end(), [](const auto& x, const auto& y) {
    return training::figure_order(x.first) < training::figure_order(y.first);
  });
  for (const auto& [name, value] : stored) {
    const training::FigureWords words = training::figure_words(name);
    figures.push_back({{"name", name},
                       {"label", words.label},
                       {"text", training::figure_text(words, value)},
                       {"about", words.about}});
  }
  json detail = {{"id", a->id},
                 {"trainee", a->trainee},
                 {"exercise", a->exercise},
                 {"status", a->status},
                 {"outcome", records::attempt_outcome(*a)},
                 {"score", a->score ? json(*a->score) : json(nullptr)},
                 {"passed", a->passed},
                 {"events", events},
                 {"metrics", metrics},
                 {"figures", figures},
                 {"deductions", deductions}};
  if (c.account->instructs()) detail["recording"] = a->recording;  // where its station wrote it
  return json_reply(request, http::status::ok, detail);
}

std::optional<Console::Response> Console::attempts_csv_file(Call& c) {
  if (!c.trainee.empty() && !db_.has_trainee(c.trainee))
    return error(c.request, http::status::not_found, "no trainee '" + core::printable(c.trainee) + "'");
  Response r = json_reply(c.request, http::status::ok, json::object());
  r.set(http::field::content_type, "text/csv; charset=utf-8");
  r.set(http::field::content_disposition, "attachment; filename=\"attempts.csv\"");
  r.body() = attempts_csv(c.trainee.empty() ? std::nullopt : std::optional(c.trainee));
  r.prepare_payload();
  return r;
}

std::optional<Console::Response> Console::trainee_evolution(Call& c) {
  if (c.trainee.empty()) return error(c.request, http::status::bad_request, "evolution of whom: ?trainee=ID");
  if (!db_.has_trainee(c.trainee))
    return error(c.request, http::status::not_found, "no trainee '" + core::printable(c.trainee) + "'");
  return json_reply(c.request, http::status::ok, evolution(c.trainee));
}

std::optional<Console::Response> Console::routes(Call& c) {
  json list = json::array();
  for (const training::Route& r : routes_)
    list.push_back(route_json(r));
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::progress(Call& c) {
  const auto& request = c.request;
  const std::string& trainee = c.trainee;
  if (trainee.empty()) return error(request, http::status::bad_request, "progress of whom: ?trainee=ID");
  if (!db_.has_trainee(trainee))
    return error(request, http::status::not_found, "no trainee '" + core::printable(trainee) + "'");
  json list = json::array();
  for (const records::EnrolmentRow& e : db_.enrolments(trainee)) {
    const auto route =
        std::find_if(routes_.begin(), routes_.end(), [&](const auto& r) { return r.id == e.route; });
    if (route == routes_.end()) continue;  // a route of another centre's folder
    const std::vector<training::Override> decided = db_.overrides(trainee, route->id);
    const training::RouteProgress p =
        training::progress(*route, db_.stage_attempts(trainee, route->id), decided);
    json stages = json::array();
    for (const training::StageProgress& sp : p.stages)
      stages.push_back({{"stage", sp.stage},
                        {"state", training::state_name(sp.state)},
                        {"attempts", sp.attempts},
                        {"attempts_allowed", sp.attempts_allowed},
                        {"passes", sp.passes},
                        {"best_score", sp.best_score ? json(*sp.best_score) : json(nullptr)},
                        {"signed_off", sp.signed_off},
                        {"missing", sp.missing}});
    json decisions = json::array();
    for (const training::Override& o : decided)
      decisions.push_back({{"stage", o.stage},
                           {"action", o.action},
                           {"reason", o.reason},
                           {"account", o.account},
                           {"at", o.at}});
    list.push_back({{"route", e.route},
                    {"enrolled_at", e.at},
                    {"next", p.next ? json(*p.next) : json(nullptr)},
                    {"complete", p.complete},
                    {"stages", stages},
                    {"decisions", decisions}});
  }
  return json_reply(request, http::status::ok, {{"trainee", trainee}, {"routes", list}});
}

std::optional<Console::Response> Console::enrol_or_decide(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  const std::optional<std::string> trainee = body ? text_field(*body, "trainee", 64, why) : std::nullopt;
  const std::optional<std::string> route_id = trainee ? text_field(*body, "route", 64, why) : std::nullopt;
  if (!route_id) return error(request, http::status::bad_request, why);
  const auto route =
      std::find_if(routes_.begin(), routes_.end(), [&](const auto& r) { return r.id == *route_id; });
  if (route == routes_.end())
    return error(request, http::status::not_found,
                 "field 'route': no route '" + core::printable(*route_id) + "'");
  if (!db_.has_trainee(*trainee))
    return error(request, http::status::not_found,
                 "field 'trainee': no trainee '" + core::printable(*trainee) + "'");
  if (c.target == "/api/enrolments") {
    const bool added = db_.enrol(*trainee, route->id, account.name);
    if (added) audit_.add(account.name, "enrol", *trainee, route->id);
    return json_reply(request, added ? http::status::created : http::status::ok,
                      {{"trainee", *trainee}, {"route", route->id}, {"enrolled", true}});
  }
  const std::optional<std::string> stage = text_field(*body, "stage", 64, why);
  const std::optional<std::string> action = stage ? text_field(*body, "action", 16, why) : std::nullopt;
  const std::optional<std::string> reason = action ? text_field(*body, "reason", 500, why) : std::nullopt;
  if (!reason) return error(request, http::status::bad_request, why);
  if (!route->stage(*stage))
    return error(request, http::status::bad_request,
                 "field 'stage': route '" + route->id + "' has no stage '" + core::printable(*stage) + "'");
  if (*action != "sign_off" && *action != "retry")
    return error(request, http::status::bad_request, "field 'action': sign_off or retry");
  try {
    db_.add_override(*trainee, route->id, {*stage, *action, *reason, account.name, ""});
  } catch (const std::out_of_range& e) {
    return error(request, http::status::conflict, e.what());
  } catch (const std::invalid_argument& e) {
    return error(request, http::status::bad_request, e.what());
  }
  audit_.add(account.name, *action, *trainee + " " + route->id + "/" + *stage, *reason);
  return json_reply(request, http::status::created,
                    {{"trainee", *trainee}, {"route", route->id}, {"stage", *stage}, {"action", *action}});
}

json Console::evolution(const std::string& trainee) {
  const std::vector<training::AttemptFigures> all = db_.attempt_figures();
  json attempts = json::array();
  json words = {{"score", figure_words_json("score")}};  // each figure's label and unit, for the plots
  for (const training::AttemptFigures& a : all) {
    if (a.trainee != trainee || a.status != "finished" || !a.score) continue;
    json skills = json::object(), metrics = json::object();
    for (const auto& [name, value] : a.metrics) {
      metrics[name] = value;
      if (name.rfind("skill_", 0) == 0) skills[name.substr(6)] = value;
      if (!words.contains(name)) words[name] = figure_words_json(name);
    }
    attempts.push_back({{"id", a.id},
                        {"exercise", a.exercise},
                        {"exercise_version", a.exercise_version},
                        {"route", a.route},
                        {"stage", a.stage},
                        {"score", *a.score},
                        {"passed", a.passed},
                        {"skills", skills},
                        {"metrics", metrics}});
  }
  json cohort = json::array(), standings = json::array();
  for (const training::Standing& s : training::standings(all, trainee)) {
    json line = {{"exercise", s.exercise},
                 {"exercise_version", s.exercise_version},
                 {"figure", s.figure},
                 {"label", training::figure_words(s.figure).label},
                 {"higher_better", s.higher_better},
                 {"best", s.best},
                 {"best_text", training::figure_text(s.figure, s.best)},
                 {"trainees", s.trainees},
                 {"percentile", s.percentile},
                 {"place", s.place},
                 {"tied", s.tied},
                 {"place_words", training::place_words(s.place, s.trainees, s.tied)}};
    if (s.figure == "score") cohort.push_back(line);
    standings.push_back(std::move(line));
  }
  json routes = json::array();
  for (const training::RouteStanding& r : records::route_standings(db_, routes_, trainee)) {
    int passed = 0;
    for (const training::StageProgress& p : r.progress.stages)
      passed += p.state == training::StageState::kPassed ? 1 : 0;
    routes.push_back({{"route", r.route.id},
                      {"name", r.route.name},
                      {"stages", r.progress.stages.size()},
                      {"passed", passed},
                      {"next", r.progress.next ? json(*r.progress.next) : json(nullptr)},
                      {"complete", r.progress.complete}});
  }
  return {{"trainee", trainee}, {"figures", words},       {"attempts", attempts},
          {"cohort", cohort},   {"standings", standings}, {"routes", routes}};
}

std::optional<Console::Response> Console::class_overview(Call& c) {
  const auto optional_number = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
  const training::ClassReportData d = records::class_report_data(db_, routes_);
  json lines = json::array();
  for (std::size_t i = 0; i < d.lines.size(); ++i) {
    const training::TraineeSummary& t = d.lines[i];
    json routes = json::array();
    for (const training::RouteStanding& r : d.routes[i]) {
      int passed = 0;
      for (const training::StageProgress& p : r.progress.stages)
        passed += p.state == training::StageState::kPassed ? 1 : 0;
      routes.push_back({{"route", r.route.id},
                        {"stages", r.progress.stages.size()},
                        {"passed", passed},
                        {"next", r.progress.next ? json(*r.progress.next) : json(nullptr)},
                        {"complete", r.progress.complete}});
    }
    lines.push_back({{"trainee", t.trainee},
                     {"name", d.names[i]},
                     {"attempts", t.attempts},
                     {"finished", t.finished},
                     {"passed", t.passed},
                     {"first_score", optional_number(t.first_score)},
                     {"last_score", optional_number(t.last_score)},
                     {"best_score", optional_number(t.best_score)},
                     {"recent_score", optional_number(t.recent_score)},
                     {"recent_skills",
                      {{"safety", optional_number(t.recent_skills[0])},
                       {"precision", optional_number(t.recent_skills[1])},
                       {"productivity", optional_number(t.recent_skills[2])}}},
                     {"trend", optional_number(t.trend)},
                     {"routes", routes}});
  }
  return json_reply(c.request, http::status::ok, lines);
}

std::optional<Console::Response> Console::compare(Call& c) {
  const auto optional_number = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
  const std::string first = query_param(c.query, "a"), second = query_param(c.query, "b");
  if (first.empty() || second.empty())
    return error(c.request, http::status::bad_request, "compare whom: ?a=ID&b=ID");
  for (const std::string& id : {first, second})
    if (!db_.has_trainee(id))
      return error(c.request, http::status::not_found, "no trainee '" + core::printable(id) + "'");
  json figures = json::array();
  for (const training::Compared& x : training::compare(db_.attempt_figures(), first, second))
    figures.push_back({{"exercise", x.exercise},
                       {"exercise_version", x.exercise_version},
                       {"figure", x.figure},
                       {"label", training::figure_words(x.figure).label},
                       {"higher_better", x.higher_better},
                       {"a", optional_number(x.first)},
                       {"b", optional_number(x.second)},
                       {"a_text", x.first ? training::figure_text(x.figure, *x.first) : ""},
                       {"b_text", x.second ? training::figure_text(x.figure, *x.second) : ""}});
  return json_reply(c.request, http::status::ok, {{"a", first}, {"b", second}, {"figures", figures}});
}

// reports: /api/reports/trainee?trainee=ID, /api/reports/class, each also as .pdf
std::optional<Console::Response> Console::report(Call& c) {
  const auto& request = c.request;
  const bool pdf = c.target.size() > 4 && c.target.compare(c.target.size() - 4, 4, ".pdf") == 0;
  const std::string page = pdf ? c.target.substr(0, c.target.size() - 4) : c.target;
  std::string html, name;
  if (page == "/api/reports/trainee") {
    if (c.trainee.empty()) return error(request, http::status::bad_request, "a report on whom: ?trainee=ID");
    if (!db_.has_trainee(c.trainee))
      return error(request, http::status::not_found, "no trainee '" + core::printable(c.trainee) + "'");
    html = training::trainee_report_html(records::trainee_report_data(db_, routes_, c.trainee));
    name = "trainee-" + c.trainee;
  } else {
    html = training::class_report_html(records::class_report_data(db_, routes_));
    name = "class";
  }
  // a file name a browser may save under: letters, digits, - and _ only
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '_';
  if (!pdf) {
    Response r = json_reply(request, http::status::ok, json::object());
    r.set(http::field::content_type, "text/html; charset=utf-8");
    r.body() = std::move(html);
    r.prepare_payload();
    return r;
  }
  audit_.add(c.account->name, "report", name, "pdf");
  // chromium prints beside the console's thread
  beside(c, printing_, kMostPrintsAtOnce, kPrintBudget,
         [this, request, html = std::move(html), name]() -> Finish {
           char folder[] = "/tmp/harboursim-pdf-XXXXXX";
           if (!mkdtemp(folder))
             return [this, request] {
               return error(request, http::status::internal_server_error, "cannot make a temporary folder");
             };
           const std::filesystem::path file = std::filesystem::path(folder) / "report.pdf";
           std::string bytes, why;
           try {
             records::print_pdf(html, file);
             std::ifstream in(file, std::ios::binary);
             bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
           } catch (const std::exception& e) {
             why = e.what();
           }
           std::error_code ignored;
           std::filesystem::remove_all(folder, ignored);
           return [this, request, bytes = std::move(bytes), why, name] {
             if (!why.empty()) return error(request, http::status::internal_server_error, why);
             Response r = json_reply(request, http::status::ok, json::object());
             r.set(http::field::content_type, "application/pdf");
             r.set(http::field::content_disposition, "attachment; filename=\"" + name + ".pdf\"");
             r.body() = bytes;
             r.prepare_payload();
             return r;
           };
         });
  return std::nullopt;
}

std::string Console::attempts_csv(const std::optional<std::string>& trainee) {
  const auto cell = [](const std::string& text) {
    std::string out = "\"";
    if (!text.empty() && std::string("=+-@\t\r").find(text[0]) != std::string::npos) out += '\'';
    for (char c : text)
      out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  // a UTF-8 byte-order mark first: spreadsheet programs otherwise read the names in the local code page
  std::string csv =
      "\xEF\xBB\xBF"
      "id,trainee,exercise,exercise_version,route,stage,status,score,passed,moves,skill_safety,skill_"
      "precision,"
      "skill_productivity\r\n";
  std::vector<records::AttemptRow> rows = db_.attempts(trainee);
  std::reverse(rows.begin(), rows.end());
  for (const records::AttemptRow& a : rows) {
    std::map<std::string, double> skills;
    for (const auto& [name, value] : db_.metrics(a.id))
      skills[name] = value;
    const auto figure = [](std::optional<double> v) {
      if (!v) return std::string();
      char text[32];
      std::snprintf(text, sizeof text, "%.6g", *v);
      return std::string(text);
    };
    const auto skill = [&](const char* name) {
      const auto found = skills.find(name);
      return figure(found == skills.end() ? std::nullopt : std::optional(found->second));
    };
    csv += std::to_string(a.id) + "," + cell(a.trainee) + "," + cell(a.exercise) + "," +
           cell(a.exercise_version) + "," + cell(a.route) + "," + cell(a.stage) + "," + cell(a.status) + "," +
           figure(a.score) + "," + (a.passed ? "1" : "0") + "," + std::to_string(a.moves) + "," +
           skill("skill_safety") + "," + skill("skill_precision") + "," + skill("skill_productivity") +
           "\r\n";
  }
  return csv;
}

}  // namespace harbour::console
