// The console's stations and teams: their statuses, commands to a station or a whole team session, the
// exercises and teams a station can run, the looks of the 3D view, the xAPI outbox.
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
#include "harbour/machines/MachineRegistry.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/records/Reports.h"
#include "harbour/scene/HandSignals.h"
#include "harbour/training/Figures.h"

namespace harbour::console {

std::string Console::stations_message() const {
  json list = json::array();
  for (const auto& [name, station] : link_.stations())
    list.push_back(status_json(name, station));
  return dump(json{{"type", "stations"}, {"stations", list}});
}

std::optional<Console::Response> Console::command(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  const std::string& station = c.segment;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const std::optional<std::string> kind = text_field(*body, "kind", 48, why);
  const std::optional<std::string> exercise =
      kind ? text_field(*body, "exercise", 128, why, false) : std::nullopt;
  const std::optional<std::string> trainee =
      exercise ? text_field(*body, "trainee", 64, why, false) : std::nullopt;
  const std::optional<std::string> route_id =
      trainee ? text_field(*body, "route", 64, why, false) : std::nullopt;
  const std::optional<std::string> team = route_id ? text_field(*body, "team", 64, why, false) : std::nullopt;
  const std::optional<std::string> role = team ? text_field(*body, "role", 32, why, false) : std::nullopt;
  if (!kind || !exercise || !trainee || !route_id || !team || !role)
    return error(request, http::status::bad_request, why);
  const auto autopilot = body->find("autopilot");
  if (autopilot != body->end() && !autopilot->is_boolean())
    return error(request, http::status::bad_request, "field 'autopilot' is not true or false");
  if (const std::string refused = io::why_refused(*kind); !refused.empty())
    return error(request, http::status::bad_request, "field 'kind': " + refused);
  if (account.signals() && !kind->starts_with("signal:") && !kind->starts_with("radio:"))
    return error(request, http::status::forbidden, "a signaller gives hand signals and radio calls only");
  const auto found = link_.stations().find(station);
  if (found == link_.stations().end())
    return error(request, http::status::not_found, "no station '" + core::printable(station) + "'");
  if (found->second.lost || found->second.gone)
    return error(request, http::status::conflict, "station " + station + " is not on the network");
  std::string to_run = *exercise;
  if (*kind == "start" && !route_id->empty()) {
    // the trainee's next stage of the route, as the station will find it in the records
    const auto route =
        std::find_if(routes_.begin(), routes_.end(), [&](const auto& r) { return r.id == *route_id; });
    if (route == routes_.end())
      return error(request, http::status::not_found,
                   "field 'route': no route '" + core::printable(*route_id) + "'");
    if (trainee->empty() || !db_.has_trainee(*trainee))
      return error(request, http::status::bad_request,
                   "field 'trainee': a route's stage is run by a trainee in the records");
    const auto enrolled = db_.enrolments(*trainee);
    if (std::none_of(enrolled.begin(), enrolled.end(), [&](const auto& e) { return e.route == route->id; }))
      return error(request, http::status::conflict,
                   *trainee + " is not enrolled in route '" + route->id + "'");
    const training::RouteProgress p = training::progress(*route, db_.stage_attempts(*trainee, route->id),
                                                         db_.overrides(*trainee, route->id));
    if (!p.next)
      return error(request, http::status::conflict,
                   p.complete ? *trainee + " has passed every stage of " + route->id
                              : "no stage of " + route->id + " is open for " + *trainee +
                                    ": an instructor decides (sign off or retry)");
    to_run = route->stage(*p.next)->exercise;
  }
  if (*kind == "start" && !team->empty()) {
    // a member of a team session: the role's exercise, as the station will find it in the team file
    if (!exercise->empty() || !route_id->empty())
      return error(request, http::status::bad_request,
                   "a team's member runs its role's exercise: no exercise or route");
    const json teams = team_list(centre().exercise_folders());
    const auto found_team =
        std::find_if(teams.begin(), teams.end(), [&](const json& t) { return t["name"] == *team; });
    if (found_team == teams.end() || found_team->contains("error"))
      return error(request, http::status::not_found,
                   "field 'team': no team '" + core::printable(*team) + "'");
    std::string roles;
    for (const json& r : (*found_team)["roles"]) {
      roles += (roles.empty() ? "" : ", ") + r["role"].get<std::string>();
      if (r["role"] == *role) to_run = r["exercise"].get<std::string>();
    }
    if (to_run.empty())
      return error(request, http::status::bad_request,
                   "field 'role': team " + *team + " has no role '" + core::printable(*role) +
                       "' (its roles: " + roles + ")");
  }
  if (*kind == "start") {
    if (to_run.empty())
      return error(request, http::status::bad_request, "start needs an exercise or a route");
    if (!trainee->empty() && !db_.has_trainee(*trainee))
      return error(request, http::status::bad_request, "no trainee '" + core::printable(*trainee) + "'");
  }
  net::StationCommand sent;
  sent.station(station);
  sent.user(account.name);
  sent.kind(*kind);
  sent.exercise(to_run);
  sent.trainee(*trainee);
  sent.route(*kind == "start" ? *route_id : "");
  if (*kind == "start" && !team->empty()) {
    sent.exercise("");  // the station takes its role's exercise from the team file
    sent.team(*team);
    sent.role(*role);
  }
  sent.autopilot(autopilot != body->end() && autopilot->get<bool>());
  const std::uint64_t id = link_.send(sent);
  pending_[id] = Pending{request, c.session, account, station, *kind, Clock::now() + kAckTimeout};
  return std::nullopt;  // answered when the station acknowledges
}

// A whole team session started as one: each of its roles on an idle station of the instructor's choice, with
// its trainee. Checked as a whole before anything is sent (every role once, each on its own station, each
// station idle on the network, each trainee in the records), so no team is left half started by a bad
// request; answered when every member has acknowledged.
std::optional<Console::Response> Console::team_start(Call& c) {
  const auto& request = c.request;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const json teams = team_list(centre().exercise_folders());
  const auto team =
      std::find_if(teams.begin(), teams.end(), [&](const json& t) { return t["name"] == c.segment; });
  if (team == teams.end() || team->contains("error"))
    return error(request, http::status::not_found, "no team '" + core::printable(c.segment) + "'");
  const auto autopilot = body->find("autopilot");
  if (autopilot != body->end() && !autopilot->is_boolean())
    return error(request, http::status::bad_request, "field 'autopilot' is not true or false");
  const auto members = body->find("members");
  if (members == body->end() || !members->is_array())
    return error(request, http::status::bad_request, "field 'members': a list of {role, station, trainee}");
  std::set<std::string> roles;
  for (const json& r : (*team)["roles"])
    roles.insert(r["role"].get<std::string>());
  struct Member {
    std::string role, station, trainee;
  };
  std::vector<Member> chosen;
  std::set<std::string> stations;
  for (const json& m : *members) {
    const std::optional<std::string> role = m.is_object() ? text_field(m, "role", 32, why) : std::nullopt;
    const std::optional<std::string> station = role ? text_field(m, "station", 64, why) : std::nullopt;
    const std::optional<std::string> trainee =
        station ? text_field(m, "trainee", 64, why, false) : std::nullopt;
    if (!trainee)
      return error(request, http::status::bad_request,
                   "field 'members': " + (why.empty() ? "an object each" : why));
    if (!roles.erase(*role))
      return error(request, http::status::bad_request,
                   "field 'members': role '" + core::printable(*role) + "' is not one of team " + c.segment +
                       "'s, or given twice");
    if (!stations.insert(*station).second)
      return error(request, http::status::bad_request,
                   "field 'members': station " + core::printable(*station) + " given twice");
    const auto found = link_.stations().find(*station);
    if (found == link_.stations().end())
      return error(request, http::status::not_found, "no station '" + core::printable(*station) + "'");
    if (found->second.lost || found->second.gone || found->second.status.state().to_string() != "idle")
      return error(request, http::status::conflict,
                   "station " + *station + " is not idle on the network (" +
                       (found->second.lost || found->second.gone ? "not seen"
                                                                 : found->second.status.state().to_string()) +
                       ")");
    if (!trainee->empty() && !db_.has_trainee(*trainee))
      return error(request, http::status::bad_request, "no trainee '" + core::printable(*trainee) + "'");
    chosen.push_back({*role, *station, *trainee});
  }
  if (!roles.empty())
    return error(request, http::status::bad_request,
                 "field 'members': no station for role '" + *roles.begin() + "' of team " + c.segment);
  TeamPending p{request, c.session, *c.account, c.segment, "start", {}, {}, Clock::now() + kAckTimeout};
  for (const Member& m : chosen) {
    net::StationCommand sent;
    sent.station(m.station);
    sent.user(c.account->name);
    sent.kind("start");
    sent.trainee(m.trainee);
    sent.team(c.segment);
    sent.role(m.role);
    sent.autopilot(autopilot != body->end() && autopilot->get<bool>());
    p.sent.emplace_back(link_.send(sent), m.station);
  }
  team_pending_.push_back(std::move(p));
  return std::nullopt;  // answered when every member has acknowledged
}

// hold, resume or stop every running member of a team session at once
std::optional<Console::Response> Console::team_command(Call& c) {
  std::string why;
  const std::optional<json> body = parse_object(c.request.body(), why);
  if (!body) return error(c.request, http::status::bad_request, why);
  const std::optional<std::string> kind = text_field(*body, "kind", 48, why);
  if (!kind) return error(c.request, http::status::bad_request, why);
  if (*kind != "hold" && *kind != "resume" && *kind != "stop")
    return error(c.request, http::status::bad_request, "a team session takes hold, resume and stop");
  TeamPending p{c.request, c.session, *c.account, c.segment, *kind, {}, {}, Clock::now() + kAckTimeout};
  for (const auto& [name, station] : link_.stations()) {
    const std::string state = station.status.state().to_string();
    if (station.lost || station.gone || station.status.team().to_string() != c.segment ||
        (state != "running" && state != "held"))
      continue;
    net::StationCommand sent;
    sent.station(name);
    sent.user(c.account->name);
    sent.kind(*kind);
    p.sent.emplace_back(link_.send(sent), name);
  }
  if (p.sent.empty())
    return error(c.request, http::status::not_found,
                 "no station runs team '" + core::printable(c.segment) + "'");
  team_pending_.push_back(std::move(p));
  return std::nullopt;  // answered when every member has acknowledged
}

std::optional<Console::Response> Console::stations(Call& c) {
  return json_reply(c.request, http::status::ok, json::parse(stations_message())["stations"]);
}

std::optional<Console::Response> Console::looks(Call& c) {
  Response r = json_reply(c.request, http::status::ok, json::object());
  r.body() = looks_;
  r.prepare_payload();
  return r;
}

// The commands an instructor gives a station, with their values' ranges: the console's panel is drawn from
// it.
std::optional<Console::Response> Console::commands(Call& c) {
  json list = json::array();
  for (const io::CommandText& command : io::station_commands()) {
    json values = json::array();
    for (const io::CommandValue& v : command.values)
      if (v.what)
        values.push_back({{"what", v.what},
                          {"unit", v.unit},
                          {"min", v.min},
                          {"max", v.max},
                          {"initial", v.initial},
                          {"step", v.step},
                          {"above_min", v.above_min},
                          {"below_max", v.below_max},
                          {"words", v.words},
                          {"hand_signal", v.hand_signal}});
    list.push_back({{"name", command.name},
                    {"label", command.label},
                    {"group", io::group_name(command.group)},
                    {"file_name", command.kind ? io::file_spelling(*command.kind) : ""},
                    {"values", values}});
  }
  // the hand signals a signal command names, each as the signaller gives it and drawn as the cab shows it
  json signals = json::array();
  for (const scene::HandSignal& s : scene::hand_signals())
    signals.push_back(
        {{"name", s.name}, {"words", s.words}, {"how", s.how}, {"strokes", scene::signal_strokes(s)}});
  return json_reply(c.request, http::status::ok, json{{"commands", list}, {"signals", signals}});
}

std::optional<Console::Response> Console::exercises(Call& c) {
  json list = json::array();
  for (const io::ExerciseCard& card : io::exercise_cards(centre().exercise_folders())) {
    const sim::MachineType* type = sim::find_machine_type(card.machine);
    json item = {{"name", card.name},
                 {"machine", card.machine},
                 {"machine_title", type ? type->title : card.machine},
                 {"faults", type ? io::instructor_faults(*type) : std::vector<std::string>{}}};
    if (card.about)
      item.update({{"title", card.about->title},
                   {"objective", card.about->objective},
                   {"difficulty", card.about->difficulty},
                   {"expected_min", card.about->expected_min}});
    if (!card.error.empty() && c.account->instructs()) item["error"] = card.error;
    list.push_back(std::move(item));
  }
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::teams(Call& c) {
  return json_reply(c.request, http::status::ok, team_list(centre().exercise_folders()));
}

std::optional<Console::Response> Console::xapi_status(Call& c) {
  std::map<std::string, int> by_state = db_.xapi_counts();
  return json_reply(c.request, http::status::ok,
                    {{"lrs", options_.lrs},
                     {"queued", by_state["queued"]},
                     {"sent", by_state["sent"]},
                     {"rejected", by_state["rejected"]},
                     {"last", xapi_ ? xapi_->last_report() : ""}});
}

}  // namespace harbour::console
