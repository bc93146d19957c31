// The console's replays: a stored attempt re-simulated and played to the browsers watching it, and an
// instructor's take-over from it.
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

std::optional<Console::Response> Console::open_replay(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const auto attempt = body->find("attempt");
  if (attempt == body->end() || !attempt->is_number_integer() || attempt->get<std::int64_t>() <= 0)
    return error(request, http::status::bad_request, "field 'attempt': an attempt id");
  const std::int64_t id = attempt->get<std::int64_t>();
  const std::optional<records::AttemptRow> row = db_.attempt(id);
  if (!row) return error(request, http::status::not_found, "no attempt " + std::to_string(id));
  if (row->recording.empty())
    return error(request, http::status::conflict, "attempt " + std::to_string(id) + " was not recorded");
  if (static_cast<int>(replays_.size()) >= Replay::kMostOpen)
    return error(request, http::status::too_many_requests,
                 "already " + std::to_string(Replay::kMostOpen) + " replays open: close one");
  Replay replay;
  std::string version, inexact;  // of the exercise replayed: the version the attempt ran, kept in the records
  try {
    const io::ExerciseSource source = records::attempt_exercise(db_, *row, exercise_folder(), inexact);
    replay.exercise = io::load_exercise_source(source);
    version = source.version;
    replay.recording = db_.read_recording_of(*row);  // the station may be another PC
  } catch (const std::exception& e) {
    return error(request, http::status::conflict, std::string("cannot replay: ") + e.what());
  }
  replay.id = next_replay_++;
  replay.attempt = id;
  replay.recording_file = row->recording;
  replay.trainee = row->trainee;
  replay.owner = account.name;
  auto [it, added] = replays_.emplace(replay.id, std::move(replay));
  Replay& r = it->second;
  try {
    r.player = std::make_unique<sim::ReplayPlayer>(r.exercise.scenario, r.recording);
  } catch (const std::exception& e) {
    replays_.erase(it);
    return error(request, http::status::conflict, std::string("cannot replay: ") + e.what());
  }
  r.scene = net::scene_message(r.player->simulation().scene(), r.attempt);
  json events = json::array();
  for (const records::EventRow& e : db_.events(id))
    events.push_back(attempt_event_json(e.at_s, e.kind, e.value));
  for (const sim::Recording::Command& given : r.recording.commands)
    events.push_back(attempt_event_json(static_cast<double>(given.step) * sim::Simulation::kStep_s,
                                        std::string("instructor ") + io::command_name(given.command.kind),
                                        0.0));
  std::sort(events.begin(), events.end(),
            [](const json& a, const json& b) { return a["at_s"].get<double>() < b["at_s"].get<double>(); });
  audit_.add(account.name, "open_replay", "attempt " + std::to_string(id), r.recording_file);
  return json_reply(request, http::status::created,
                    {{"replay", r.id},
                     {"station", "replay-" + std::to_string(r.id)},
                     {"attempt", id},
                     {"exercise", r.exercise.name},
                     {"exercise_version", version},
                     {"trainee", r.trainee},
                     {"duration_s", static_cast<double>(r.recording.total_steps) * sim::Simulation::kStep_s},
                     {"complete", r.recording.complete},
                     {"exact", inexact.empty()},
                     {"note", inexact},
                     {"events", events}});
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
  const double duration_s = static_cast<double>(r.recording.total_steps) * sim::Simulation::kStep_s;
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
      r.player->seek(static_cast<std::int64_t>(std::llround(*at / sim::Simulation::kStep_s)));
    } catch (const std::exception& e) {
      return error(request, http::status::conflict, std::string("cannot seek: ") + e.what());
    }
    r.position_steps = static_cast<double>(r.player->simulation().steps());
    r.bulk = {};  // the material as it was then: copied whole again (tile versions restart with the state)
  } else if (*action == "take-over") {
    // the attempt continues live at a station from the moment shown, as a new attempt of a trainee
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
    sent.step(r.player->simulation().steps());
    const std::uint64_t command = link_.send(sent);
    pending_[command] = Pending{request,
                                session,
                                account,
                                *station,
                                "take-over of attempt " + std::to_string(r.attempt) + " at step " +
                                    std::to_string(r.player->simulation().steps()),
                                Clock::now() + kAckTimeout};
    return std::nullopt;
  } else if (*action == "close") {
    audit_.add(account.name, "close_replay", "attempt " + std::to_string(r.attempt), "");
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
  const sim::Simulation& sim = r.player->simulation();
  sim.write_snapshot(*r.snapshot);
  json state =
      state_json("replay-" + std::to_string(r.id),
                 net::state_message(*r.snapshot, sim.scene().entities.size(), r.attempt), &r.scene, view);
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
    r.position_steps =
        std::min(r.position_steps + dt * r.speed / sim::Simulation::kStep_s,
                 static_cast<double>(r.player->simulation().steps() + Replay::kMostStepsPerPoll));
    try {
      r.player->advance_to(static_cast<std::int64_t>(r.position_steps));
    } catch (const std::exception&) {
      r.playing = false;  // a damaged recording: it stops where it could go no further
    }
    if (r.player->simulation().steps() >= r.player->total_steps()) r.playing = false;
  }
}

}  // namespace harbour::console
