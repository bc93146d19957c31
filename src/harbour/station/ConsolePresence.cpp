#include "harbour/station/ConsolePresence.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "harbour/core/Text.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/scene/HandSignals.h"

namespace harbour::station {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kStatusPeriod = std::chrono::milliseconds(static_cast<int>(net::kStatusPeriod_s * 1e3));
constexpr auto kStatePeriod = std::chrono::milliseconds(100);  // 10 Hz: plots and the console's 3D view
constexpr auto kBulkPeriod = std::chrono::seconds(1);          // the material's surfaces: it moves slowly

net::StationStatus base_status(const std::string& state) {
  net::StationStatus s;
  s.host(core::host_name());
  s.process_id(static_cast<std::uint32_t>(getpid()));
  s.state(state);
  s.keeping_real_time(true);
  return s;
}

// the commands a running loop takes as they are
std::optional<LoopCommand::Kind> loop_kind(const std::string& kind) {
  using K = LoopCommand::Kind;
  if (kind == "hold") return K::kHold;
  if (kind == "resume") return K::kResume;
  if (kind == "step") return K::kSingleStep;
  return std::nullopt;
}

}  // namespace

IdlePresence::IdlePresence(net::StationLink& link, const std::string& last_message)
    : link_(link), message_(last_message) {}

std::optional<StartRequest> IdlePresence::service() {
  std::optional<StartRequest> start;
  for (const net::StationCommand& c : link_.take_commands()) {
    const std::string kind = c.kind().to_string();
    const bool starts = kind == "start" || kind == "take-over";
    if (starts && !start) {
      start = StartRequest{
          c.exercise().to_string(), c.trainee().to_string(), c.user().to_string(), c.route().to_string(),
          c.team().to_string(),     c.role().to_string(),    c.autopilot(),        std::nullopt};
      if (kind == "take-over") start->take_over = TakeOverFrom{c.recording().to_string(), c.step()};
      link_.acknowledge(
          c, true,
          (kind == "start" ? "starting " : "taking over ") +
              (start->team.empty() ? start->exercise : start->role + " of team " + start->team));
    } else {
      link_.acknowledge(
          c, false,
          starts ? "already starting an exercise" : "nothing runs at this station: start an exercise first");
    }
  }
  const Clock::time_point now = Clock::now();
  if (start || now >= next_status_) {
    net::StationStatus s = base_status(start ? "starting" : "idle");
    if (start) {
      s.exercise(start->exercise);
      s.trainee(start->trainee);
      s.team(start->team);
      s.role(start->role);
    }
    s.message(message_.substr(0, 255));
    link_.publish(s);
    next_status_ = now + kStatusPeriod;
  }
  return start;
}

AttemptPresence::AttemptPresence(net::StationLink& link, Session& session,
                                 const sim::ExerciseSettings& exercise, const std::string& trainee,
                                 const scene::SceneDescription& scene)
    : link_(link), session_(session), exercise_(exercise), trainee_(trainee), scene_(scene) {
  link_.publish(net::scene_message(scene_, session.attempt()));
}

void AttemptPresence::rename_entity(std::size_t index, const std::string& name) {
  if (index >= scene_.entities.size() || scene_.entities[index].name == name) return;
  scene_.entities[index].name = name;
  link_.publish(net::scene_message(scene_, session_.attempt()));
}

net::StationStatus AttemptPresence::status(const std::string& state, const scene::Snapshot* snapshot) const {
  net::StationStatus s = base_status(state);
  s.machine(scene_.machine);
  s.exercise(exercise_.name);
  s.trainee(trainee_);
  s.team(team_);
  s.role(role_);
  s.attempt(session_.attempt());
  s.time_limit_s(exercise_.rules.time_limit_s);
  const LoopStats loop = session_.loop().stats();
  s.real_time_factor(loop.real_time_factor);
  s.late_ticks(loop.late_ticks);
  s.skipped_ticks(loop.skipped_ticks);
  s.keeping_real_time(loop.keeping_real_time);
  const sim::Metrics m = session_.metrics();
  s.score(session_.score().total);
  s.moves_done(m.moves_completed);
  s.moves_total(static_cast<std::int32_t>(exercise_.moves.size()));
  s.collisions(m.collisions);
  if (snapshot) {
    s.time_s(snapshot->time_s);
    s.devices_missing(snapshot->devices_missing);
    s.physics_warnings(snapshot->warnings);
    s.diverged(snapshot->diverged);
  }
  return s;
}

void AttemptPresence::publish_state(const scene::Snapshot& snapshot) {
  link_.publish(net::state_message(snapshot, scene_.entities.size(), session_.attempt()));
}

double AttemptPresence::published_time_s() {
  const scene::Snapshot* snapshot = session_.loop().latest_snapshot(kConsoleReader);
  return snapshot ? snapshot->time_s : 0.0;
}

const scene::Snapshot* AttemptPresence::snapshot() {
  return session_.loop().latest_snapshot(kConsoleReader);
}

bool AttemptPresence::apply(const net::StationCommand& command, std::string& answer, Next& next) {
  const std::string kind = command.kind().to_string();
  if (kind == "start" || kind == "take-over") {
    answer = "already running " + exercise_.name + ": stop it first";
    return false;
  }
  if (const std::string refused = io::why_refused(kind); !refused.empty()) {
    answer = refused;  // not the table's, or a value out of its range: nothing done
    return false;
  }
  if (kind == "stop" || kind == "reset") {
    next = kind == "stop" ? Next::kStop : Next::kReset;
    answer = kind == "stop" ? "stopping: with goals left the attempt is stored as ended by the instructor"
                            : "resetting: the attempt is stored as ended by the instructor and starts again";
    return true;
  }
  if (kind == "mute" || kind == "unmute" || kind.starts_with("volume:") || kind.starts_with("radio:"))
    return apply_sound(kind, answer);
  LoopCommand loop;
  if (const auto k = loop_kind(kind)) {
    loop.kind = *k;
    if (*k == LoopCommand::Kind::kSingleStep && !was_held_) {
      answer = "single steps only while held";
      return false;
    }
  } else {
    try {
      loop.kind = LoopCommand::Kind::kInstructor;
      loop.instructor = io::parse_instructor_command("0:" + kind).command;
    } catch (const std::invalid_argument& e) {
      answer = e.what();
      return false;
    }
  }
  if (!session_.loop().post(loop, &answer)) return false;
  answer = "done: " + kind;
  if (loop.kind == LoopCommand::Kind::kInstructor &&
      loop.instructor.kind == sim::InstructorCommand::Kind::kSignal)
    answer = say_signal(loop.instructor);
  return true;
}

std::string AttemptPresence::say_signal(const sim::InstructorCommand& command) {
  // the signaller calls it on the radio as well as showing it, where the cab has one
  const scene::HandSignal& signal = scene::hand_signals()[static_cast<std::size_t>(command.value)];
  const std::string shown = "done: the operator sees \"" + std::string(signal.words) + "\"";
  if (!sound_) return shown + " (no sound here to call it on the radio)";
  try {
    sound_->say(std::string(signal.words));
  } catch (const audio::AudioError& e) {
    return shown + " (not called on the radio: " + e.what() + ")";
  }
  return shown + " and hears it on the radio";
}

bool AttemptPresence::apply_sound(const std::string& kind, std::string& answer) {
  if (!sound_) {
    answer = "this station plays no sound (no window, no sound device, or its profile says off)";
    return false;
  }
  if (kind.starts_with("radio:")) {
    const std::string text = kind.substr(std::string("radio:").size());
    try {
      sound_->say(text);
    } catch (const audio::AudioError& e) {
      answer = e.what();
      return false;
    }
    answer = "done: on the radio, \"" + text + "\"";
    return true;
  }
  if (kind == "mute" || kind == "unmute") {
    sound_->set_muted(kind == "mute");
    answer = kind == "mute" ? "done: sound muted" : "done: sound on";
    return true;
  }
  const double value =
      std::strtod(kind.c_str() + std::string("volume:").size(), nullptr);  // in range, checked
  sound_->set_volume(value / 100.0);
  answer = "done: volume " + std::to_string(static_cast<int>(std::lround(value))) + " %" +
           (sound_->muted() ? " (muted)" : "");
  return true;
}

void AttemptPresence::offer_picture(std::vector<std::uint8_t> jpeg, int width, int height, double time_s) {
  if (jpeg.size() > kMostPictureBytes) return;  // a picture past the topic's bound is not sent
  net::StationPicture p;
  p.attempt(session_.attempt());
  p.time_s(time_s);
  p.width(static_cast<std::uint16_t>(width));
  p.height(static_cast<std::uint16_t>(height));
  p.jpeg(std::move(jpeg));
  const std::lock_guard lock(picture_mutex_);
  picture_ = std::move(p);
}

AttemptPresence::Next AttemptPresence::service() {
  Next next = Next::kRun;
  bool changed = false;
  {
    std::optional<net::StationPicture> picture;
    {
      const std::lock_guard lock(picture_mutex_);
      picture.swap(picture_);
    }
    if (picture) link_.publish(std::move(*picture));
  }
  for (const net::StationCommand& c : link_.take_commands()) {
    if (c.kind().to_string() == "watch") {  // a console shows this station: its pictures are wanted a while
      watched_until_ns_.store((std::chrono::steady_clock::now() + kWatchedFor).time_since_epoch().count());
      link_.acknowledge(c, true, "watched");
      continue;
    }
    std::string answer;
    const bool ok = apply(c, answer, next);
    link_.acknowledge(c, ok, answer);
    if (ok) {
      net::StationEvent e;
      e.attempt(session_.attempt());
      e.time_s(published_time_s());
      e.kind("instructor");
      e.text((c.kind().to_string() + " by " + c.user().to_string()).substr(0, 255));
      link_.publish(e);
      changed = true;
    }
  }
  const sim::Metrics now = session_.metrics();
  for (const sim::CountedEvent& counted : sim::counted_events(seen_, now)) {
    net::StationEvent e;
    e.attempt(session_.attempt());
    e.time_s(now.time_s);
    e.kind(counted.kind);
    e.value(counted.value);
    link_.publish(e);
  }
  for (int n = seen_.moves_completed; n < now.moves_completed; ++n) {
    net::StationEvent e;
    e.attempt(session_.attempt());
    e.time_s(now.time_s);
    e.kind("move_done");
    e.value(n + 1);
    link_.publish(e);
    changed = true;
  }
  seen_ = now;
  const Clock::time_point t = Clock::now();
  const scene::Snapshot* snapshot = this->snapshot();  // stable until the next read (none below)
  const bool held = snapshot && snapshot->held;
  if (held != was_held_) changed = true;
  was_held_ = held;
  if (changed || t >= next_status_) {
    link_.publish(status(held ? "held" : "running", snapshot));
    next_status_ = t + kStatusPeriod;
  }
  if (snapshot && t >= next_state_) {
    publish_state(*snapshot);
    next_state_ = t + kStatePeriod;
  }
  if (t >= next_bulk_) {
    if (const scene::BulkView* bulk = session_.loop().latest_bulk(kConsoleReader))
      link_.publish(net::bulk_message(*bulk, session_.attempt(), published_time_s()));
    next_bulk_ = t + kBulkPeriod;
  }
  return next;
}

void AttemptPresence::note(const std::string& kind, const std::string& text) {
  net::StationEvent e;
  e.attempt(session_.attempt());
  e.time_s(published_time_s());
  e.kind(kind.substr(0, 32));
  e.text(text.substr(0, 255));
  link_.publish(e);
}

std::string attempt_outcome(const SessionResult& r) {
  const bool scored = r.status == "finished" || r.status == "ended_by_instructor";
  const std::string how = r.status == "finished"              ? (r.score.passed ? "passed" : "not passed")
                          : r.status == "ended_by_instructor" ? "ended by the instructor"
                                                              : r.status;
  char score[32];
  std::snprintf(score, sizeof score, ", score %.1f", r.score.total);
  return "attempt " + std::to_string(r.attempt) + " " + how + (scored ? score : "");
}

void AttemptPresence::publish_end(const SessionResult& result) {
  net::StationStatus s = status("finished", nullptr);
  s.score(result.score.total);
  s.moves_done(result.metrics.moves_completed);
  s.collisions(result.metrics.collisions);
  s.time_s(result.metrics.time_s);
  s.message(attempt_outcome(result).substr(0, 255));
  link_.publish(s);
  net::StationEvent e;
  e.attempt(result.attempt);
  e.time_s(result.metrics.time_s);
  e.kind("attempt_end");
  e.value(result.score.total);
  e.text(result.status);
  link_.publish(e);
}

}  // namespace harbour::station
