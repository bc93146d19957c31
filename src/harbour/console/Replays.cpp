// The console's replays: a stored attempt re-simulated and played to the browsers watching it, and an
// instructor's take-over from it.
#include "harbour/console/ConsoleServer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
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

namespace {

// Seconds since the epoch of a UTC time as the records keep it ("2026-12-07T07:13:22.888Z")
std::optional<double> utc_seconds(const std::string& iso) {
  std::tm t{};
  double seconds = 0.0;
  if (std::sscanf(iso.c_str(), "%d-%d-%dT%d:%d:%lf", &t.tm_year, &t.tm_mon, &t.tm_mday, &t.tm_hour, &t.tm_min,
                  &seconds) != 6)
    return std::nullopt;
  t.tm_year -= 1900;
  t.tm_mon -= 1;
  return static_cast<double>(timegm(&t)) + seconds;
}

// A stored attempt opened to be replayed: its exercise as it ran and its recording
struct OpenedAttempt {
  records::AttemptRow row;
  sim::ExerciseSettings exercise;
  std::string version, inexact;
  sim::Recording recording;  // moved into the replay's player once the members' starts are found
};

// A team session's members in its team file's order of roles (the crane before its trucks), and when each
// started on the first's clock: a truck from the hand-off both recorded, else from the records' start times
// (the session at real time)
std::vector<double> member_starts(std::vector<OpenedAttempt>& members,
                                  const std::vector<std::string>& folders) {
  std::optional<io::Team> team;
  if (net::why_bad_node_name(members.front().row.team).empty()) try {
      team = io::load_team(records::shipped_data_folder() + "/teams/" + members.front().row.team + ".yaml",
                           folders);
    } catch (const std::exception&) {  // a team file since removed or in error: the records' times alone
    }
  const auto role_index = [&](const std::string& role) {
    for (std::size_t k = 0; team && k < team->roles.size(); ++k)
      if (team->roles[k].role == role) return k;
    return std::size_t{1000};
  };
  std::stable_sort(members.begin(), members.end(), [&](const OpenedAttempt& a, const OpenedAttempt& b) {
    return role_index(a.row.team_role) < role_index(b.row.team_role);
  });
  std::vector<double> starts(members.size(), 0.0);
  const std::optional<double> first = utc_seconds(members.front().row.started_at);
  for (std::size_t k = 0; k < members.size(); ++k) {
    const std::optional<double> at = utc_seconds(members[k].row.started_at);
    starts[k] = first && at ? *at - *first : 0.0;
  }
  for (std::size_t c = 0; team && c < members.size(); ++c) {
    const std::size_t crane = role_index(members[c].row.team_role);
    if (crane >= team->roles.size()) continue;
    const std::vector<std::string>& trucks = team->roles[crane].trucks;
    for (std::size_t slot = 0; slot < trucks.size(); ++slot)
      for (std::size_t t = 0; t < members.size(); ++t)
        if (members[t].row.team_role == trucks[slot])
          if (const std::optional<double> start =
                  sim::truck_start_s(members[c].recording, static_cast<int>(slot), members[t].recording))
            starts[t] = starts[c] + *start;
  }
  return starts;
}

// the scene sent again where the player's names changed: a box handed onto a truck is drawn by its name
// (the scene's key moves on with the player's names_version())
void name_scene(Replay& r) {
  if (r.scene_names == r.player->names_version()) return;
  r.scene = net::scene_message(r.player->scene(), r.attempt);
  r.scene_names = r.player->names_version();
}

}  // namespace

std::optional<Console::Response> Console::open_replay(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  // one attempt, or a team session's every member
  std::vector<records::AttemptRow> rows;
  std::string session;
  if (body->contains("session")) {
    const std::optional<std::string> named = text_field(*body, "session", 160, why);
    if (!named) return error(request, http::status::bad_request, why);
    session = *named;
    rows = db_.session_attempts(session);
    if (rows.empty())
      return error(request, http::status::not_found, "no team session '" + core::printable(session) + "'");
  } else {
    const auto attempt = body->find("attempt");
    if (attempt == body->end() || !attempt->is_number_integer() || attempt->get<std::int64_t>() <= 0)
      return error(request, http::status::bad_request,
                   "field 'attempt': an attempt id (or 'session': a team session's name)");
    const std::int64_t id = attempt->get<std::int64_t>();
    std::optional<records::AttemptRow> row = db_.attempt(id);
    if (!row) return error(request, http::status::not_found, "no attempt " + std::to_string(id));
    rows.push_back(std::move(*row));
  }
  if (static_cast<int>(replays_.size()) >= Replay::kMostOpen)
    return error(request, http::status::too_many_requests,
                 "already " + std::to_string(Replay::kMostOpen) + " replays open: close one");
  for (const records::AttemptRow& row : rows)
    if (row.recording.empty())
      return error(request, http::status::conflict,
                   "attempt " + std::to_string(row.id) + (session.empty() ? "" : " (" + row.team_role + ")") +
                       " was not recorded");
  std::vector<OpenedAttempt> members;
  try {
    for (records::AttemptRow& row : rows) {
      OpenedAttempt m;
      const io::ExerciseSource source = records::attempt_exercise(db_, row, exercise_folder(), m.inexact);
      m.exercise = io::load_exercise_source(source);
      m.version = source.version;
      m.recording = db_.read_recording_of(row);  // the station may be another PC
      m.row = std::move(row);
      members.push_back(std::move(m));
    }
  } catch (const std::exception& e) {
    return error(request, http::status::conflict, std::string("cannot replay: ") + e.what());
  }
  const std::vector<double> starts =
      session.empty() ? std::vector<double>{0.0} : member_starts(members, centre().exercise_folders());
  std::vector<sim::SessionPlayer::Member> played;
  for (std::size_t k = 0; k < members.size(); ++k)
    played.push_back({members[k].row.team_role, members[k].exercise.scenario, std::move(members[k].recording),
                      starts[k]});  // (the player keeps each recording; none is copied)
  Replay replay;
  try {
    replay.player = std::make_unique<sim::SessionPlayer>(std::move(played));
  } catch (const std::exception& e) {
    return error(request, http::status::conflict, std::string("cannot replay: ") + e.what());
  }
  const OpenedAttempt& first = members.front();
  replay.id = next_replay_++;
  replay.attempt = first.row.id;
  replay.session = session;
  replay.exercise = first.exercise;
  replay.recording_file = first.row.recording;
  replay.trainee = first.row.trainee;
  replay.owner = account.name;
  replay.scene = net::scene_message(replay.player->scene(), replay.attempt);
  // what happened when, each member's on the session's clock (a team's said with its role)
  json events = json::array(), roles = json::array();
  bool complete = true;
  std::string inexact;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const OpenedAttempt& m = members[k];
    const double start_s = replay.player->member(k).start_s;
    const std::string who = session.empty() ? "" : m.row.team_role + ": ";
    const auto happened = [&](double at_s, const std::string& kind, double value) {
      json event = attempt_event_json(start_s + at_s, kind, value);
      event["text"] = who + event["text"].get<std::string>();  // "tractor_1: move 1 done"
      events.push_back(std::move(event));
    };
    for (const records::EventRow& e : db_.events(m.row.id))
      happened(e.at_s, e.kind, e.value);
    const sim::Recording& recording = replay.player->member(k).recording;
    for (const sim::Recording::Command& given : recording.commands)
      happened(static_cast<double>(given.step) * sim::Simulation::kStep_s,
               "instructor " + std::string(io::command_name(given.command.kind)), 0.0);
    complete = complete && recording.complete;
    if (!m.inexact.empty()) inexact += (inexact.empty() ? "" : "; ") + who + m.inexact;
    roles.push_back({{"role", m.row.team_role},
                     {"attempt", m.row.id},
                     {"trainee", m.row.trainee},
                     {"exercise", m.exercise.name},
                     {"start_s", start_s}});
  }
  std::sort(events.begin(), events.end(),
            [](const json& a, const json& b) { return a["at_s"].get<double>() < b["at_s"].get<double>(); });
  auto [it, added] = replays_.emplace(replay.id, std::move(replay));
  Replay& r = it->second;
  audit_.add(account.name, "open_replay",
             session.empty() ? "attempt " + std::to_string(r.attempt) : "team session " + session,
             r.recording_file);
  json info = {{"replay", r.id},
               {"station", "replay-" + std::to_string(r.id)},
               {"attempt", r.attempt},
               {"exercise", r.exercise.name},
               {"exercise_version", first.version},
               {"trainee", r.trainee},
               {"duration_s", r.player->duration_s()},
               {"complete", complete},
               {"exact", inexact.empty()},
               {"note", inexact},
               {"events", events}};
  if (!session.empty()) {
    info["session"] = session;
    info["members"] = roles;
  }
  return json_reply(request, http::status::created, info);
}

std::optional<Console::Response> Console::control_replay(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  const std::int64_t id = c.segment_id;
  const std::shared_ptr<HttpSession>& session = c.session;
  const auto found = replays_.find(id);
  if (found == replays_.end())
    return error(request, http::status::not_found, "no replay " + std::to_string(id));
  Replay& r = found->second;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  const std::optional<std::string> action = body ? text_field(*body, "action", 16, why) : std::nullopt;
  if (!action) return error(request, http::status::bad_request, why);
  const auto number = [&](const char* field, double low, double high) -> std::optional<double> {
    const auto f = body->find(field);
    if (f == body->end() || !f->is_number() || !(f->get<double>() >= low && f->get<double>() <= high)) {
      why = std::string("field '") + field + "': a number from " + std::to_string(low) + " to " +
            std::to_string(high);
      return std::nullopt;
    }
    return f->get<double>();
  };
  const double duration_s = r.player->duration_s();
  if (*action == "play" || *action == "pause") {
    r.playing = *action == "play";
    if (body->contains("speed")) {
      const std::optional<double> speed = number("speed", 0.25, 8.0);
      if (!speed) return error(request, http::status::bad_request, why);
      r.speed = *speed;
    }
    r.last_poll = Clock::now();
  } else if (*action == "seek") {
    const std::optional<double> at = number("at_s", 0.0, duration_s);
    if (!at) return error(request, http::status::bad_request, why);
    try {
      r.player->seek(*at);
    } catch (const std::exception& e) {
      return error(request, http::status::conflict, std::string("cannot seek: ") + e.what());
    }
    r.position_s = r.player->time_s();
    name_scene(r);
    r.bulk = {};  // the material as it was then: copied whole again (tile versions restart with the state)
  } else if (*action == "take-over") {
    // the attempt continues live at a station from the moment shown, as a new attempt of a trainee
    if (r.player->members() > 1)
      return error(request, http::status::conflict,
                   "a team session's replay: open the attempt of the member to take over");
    const std::optional<std::string> station = text_field(*body, "station", 64, why);
    const std::optional<std::string> trainee =
        station ? text_field(*body, "trainee", 64, why, false) : std::nullopt;
    if (!trainee) return error(request, http::status::bad_request, why);
    const auto found_station = link_.stations().find(*station);
    if (found_station == link_.stations().end() || found_station->second.lost || found_station->second.gone)
      return error(request, http::status::not_found,
                   "no station '" + core::printable(*station) + "' on the network");
    if (!trainee->empty() && !db_.has_trainee(*trainee))
      return error(request, http::status::bad_request, "no trainee '" + core::printable(*trainee) + "'");
    const auto autopilot = body->find("autopilot");
    r.playing = false;
    net::StationCommand sent;
    sent.station(*station);
    sent.user(account.name);
    sent.kind("take-over");
    sent.exercise(r.exercise.name);
    sent.trainee(trainee->empty() ? r.trainee : *trainee);
    sent.autopilot(autopilot != body->end() && autopilot->is_boolean() && autopilot->get<bool>());
    sent.recording(r.recording_file);
    const std::int64_t step = r.player->player(0).simulation().steps();
    sent.step(step);
    const std::uint64_t command = link_.send(sent);
    pending_[command] =
        Pending{request,
                session,
                account,
                *station,
                "take-over of attempt " + std::to_string(r.attempt) + " at step " + std::to_string(step),
                Clock::now() + kAckTimeout};
    return std::nullopt;
  } else if (*action == "close") {
    audit_.add(account.name, "close_replay",
               r.session.empty() ? "attempt " + std::to_string(r.attempt) : "team session " + r.session, "");
    replays_.erase(found);
    return json_reply(request, http::status::ok, {{"closed", id}});
  } else {
    return error(request, http::status::bad_request, "action: play, pause, seek, take-over or close");
  }
  json state = replay_state(r);
  state["playing"] = r.playing;
  state["speed"] = r.speed;
  return json_reply(request, http::status::ok, state);
}

json Console::replay_state(Replay& r, bool view) {
  r.player->write_snapshot(*r.snapshot);
  json state = state_json("replay-" + std::to_string(r.id),
                          net::state_message(*r.snapshot, r.player->scene().entities.size(), r.attempt),
                          &r.scene, view);
  state["held"] = !r.playing;
  state["replay"] = r.id;
  state["checkpoint_mismatch"] = r.player->first_mismatch().has_value();
  return state;
}

void Console::push_state(LiveSocket& socket, const std::string& station, const net::StationScene* scene,
                         std::uint64_t scene_count, const std::function<json(bool)>& state_of) {
  if (socket.wants_view() && scene) {
    const std::string key =
        station + " " + std::to_string(scene->attempt()) + " " + std::to_string(scene_count);
    if (socket.scene_sent() != key) {
      socket.send(dump(scene_json(station, *scene)));
      socket.scene_sent() = key;
    }
  }
  socket.send(dump(state_of(socket.wants_view())));
}

void Console::play_replays(Clock::time_point now) {
  for (auto& [id, r] : replays_) {
    const double dt = std::chrono::duration<double>(now - r.last_poll).count();
    r.last_poll = now;
    if (!r.playing) continue;
    // each member at most kMostStepsPerPoll steps a poll: the server stays responsive
    r.position_s = std::min(r.position_s + dt * r.speed,
                            r.player->time_s() + static_cast<double>(Replay::kMostStepsPerPoll) *
                                                     sim::Simulation::kStep_s /
                                                     static_cast<double>(r.player->members()));
    try {
      r.player->advance_to(r.position_s);
    } catch (const std::exception&) {
      r.playing = false;  // a damaged recording: it stops where it could go no further
    }
    name_scene(r);
    if (r.player->time_s() >= r.player->duration_s()) r.playing = false;
  }
}

}  // namespace harbour::console
