#include "harbour/station/Session.h"

#include <chrono>
#include <stdexcept>

#include "harbour/core/Text.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/station/ThreadRole.h"

namespace harbour::station {
namespace {
constexpr std::int64_t kPublishEverySteps = 50;  // the figures for displays: 20 times a simulated second
}  // namespace

Session::Session(const sim::ExerciseSettings& exercise, const SessionOptions& options)
    : exercise_(exercise),
      options_(options),
      simulation_(std::make_unique<sim::Simulation>(exercise.scenario)),
      evaluator_(exercise),
      recorder_(exercise.name, simulation_->control_table()) {
  db_ = std::make_unique<records::RecordsStore>(options.database);
  if (!db_->has_trainee(options.trainee))
    throw std::runtime_error("no trainee '" + options.trainee + "' (add it with: harboursim trainees add)");
  std::optional<std::int64_t> parent;
  std::int64_t branch_step = 0;
  if (options.take_over) {
    // only an attempt the centre's records know is continued: a command names no other file to read
    const std::optional<records::AttemptRow> taken = db_->attempt_recorded_at(options.take_over->recording);
    if (!taken)
      throw std::runtime_error("take-over refused: no stored attempt was recorded at '" +
                               core::printable(options.take_over->recording) + "'");
    parent = taken->id;
    const sim::Recording original = db_->read_recording_of(*taken);  // (made on another PC, maybe)
    if (original.scenario != exercise.name)
      throw std::runtime_error(options.take_over->recording + " was recorded on exercise '" +
                               original.scenario + "', not '" + exercise.name + "'");
    if (options.take_over->step < 0 || options.take_over->step > original.total_steps)
      throw std::runtime_error("take-over at step " + std::to_string(options.take_over->step) +
                               ": outside the recording (0 to " + std::to_string(original.total_steps) + ")");
    // the evaluation sees the original attempt up to the take-over
    sim::TakeOver branch = sim::take_over(
        exercise.scenario, original, options.take_over->recording, options.take_over->step,
        [this](const sim::Simulation& s, const scene::Controls& in) { evaluator_.observe(s, in); });
    simulation_ = std::move(branch.simulation);
    recorder_ = std::move(branch.recorder);
    levers_before_start_ = branch.levers;
    branch_step = simulation_->steps();
    moves_before_start_ = evaluator_.metrics().moves_completed;
  }
  sim::reserve_lists(metrics_);  // copied into on the step thread, without allocating
  metrics_ = evaluator_.metrics();
  goals_met_ = evaluator_.goals_met();
  handed_ = stored_ = sim::progress(metrics_);  // a take-over's history is the parent attempt's
  kept_steps_ = simulation_->steps();
  if (!options.record.empty()) {
    writer_.emplace(options.record, recorder_.recording());
    recorder_.set_sink(&*writer_);
  }
  attempt_ =
      db_->begin_attempt({options.trainee, exercise.name, parent, branch_step, options.record, options.route,
                          options.stage, options.source.version, options.source, options.autopilot});
  LoopSettings loop = options.loop;
  loop.checkpoint_every_steps = sim::Recorder::kCheckpointEvery;
  loop.keyframe_every_steps = writer_ ? sim::Recorder::kKeyframeEvery : 0;
  loop_ = std::make_unique<RealTimeLoop>(*simulation_, loop);
  loop_->set_observer([this](const sim::Simulation& s, const scene::Controls& in) { evaluate(s, in); });
  // the exercise bounds the run: its goals met (the evaluation says so on the step it happens), or its time
  // and overtime past
  const double stop_at_s = exercise.rules.time_limit_s + exercise.rules.overtime_s;
  loop_->set_stop_when(
      [this, stop_at_s](const sim::Simulation& s) { return over_.load() || s.time_s() >= stop_at_s; });
}

Session::~Session() {
  if (!finished_) {
    try {
      finish(SessionEnd::kInterrupted);
    } catch (...) {  // the database itself failed: its next opening marks the attempt interrupted
    }
  }
}

void Session::start() {
  keeper_ = std::thread([this] {
    take_role(ThreadRole::kRecordKeeper);
    keep();
  });
  loop_->start();
}

sim::Metrics Session::metrics() const {
  const std::lock_guard lock(metrics_mutex_);
  return metrics_;
}

sim::Score Session::score() const {
  const std::lock_guard lock(metrics_mutex_);
  return sim::score_of(exercise_, metrics_, goals_met_);  // here: a score's reasons allocate
}

void Session::note_event(const std::string& kind, double value) {
  const std::lock_guard lock(notes_mutex_);
  notes_.emplace_back(kind, value);
}

void Session::store_notes() {
  std::vector<std::pair<std::string, double>> notes;
  {
    const std::lock_guard lock(notes_mutex_);
    notes.swap(notes_);
  }
  for (const auto& [kind, value] : notes)
    db_->record_event(attempt_, static_cast<double>(kept_steps_.load()) * sim::Simulation::kStep_s, kind,
                      value);
}

void Session::evaluate(const sim::Simulation& simulation, const scene::Controls& controls) {
  // the step thread: the evaluation sees every step as it is taken; a move done or an event counted goes to
  // the keeper at once, stamped with this step's time
  evaluator_.observe(simulation, controls);
  const sim::Progress now = sim::progress(evaluator_.metrics());
  const bool grew = now.grew_since(handed_);
  if (grew) {
    handed_ = now;
    // 4096 looks behind, the keeper has stalled: the step waits for it (unless it failed, which ends the run)
    while (!progress_.push(now) && keeper_error_.empty())
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (grew || simulation.steps() % kPublishEverySteps == 0) publish_metrics();
  if (evaluator_.finished() || simulation.diverged()) over_ = true;
}

void Session::publish_metrics() {
  const std::lock_guard lock(metrics_mutex_);  // held by a reader only while it copies
  metrics_ = evaluator_.metrics();
  goals_met_ = evaluator_.goals_met();
}

void Session::keep() {
  try {
    for (;;) {
      store_notes();
      if (keep_what_is_handed()) continue;
      if (loop_done_.load()) {
        if (!keep_what_is_handed()) break;  // the loop has stopped: everything it handed on is kept
        continue;
      }
      // waking 100 times a second, not 1000: the rings hold 32 s of steps and 4096 looks of progress
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  } catch (const std::exception& e) {
    keeper_error_ = e.what();  // reported by finish(); the loop is told to stop
    over_ = true;
  }
}

bool Session::keep_what_is_handed() {
  bool kept = false;
  StepRecord record;
  for (int n = 0; n < 1000 && loop_->records().pop(record); ++n, kept = true)
    keep(record);
  sim::Progress now;
  while (progress_.pop(now)) {
    records::record_progress(*db_, attempt_, stored_, now);
    stored_ = now;
    kept = true;
  }
  return kept;
}

void Session::keep(const StepRecord& record) {
  switch (record.kind) {
    case StepRecord::Kind::kCommand:
      if (writer_) recorder_.on_command(record.step, record.command);
      break;
    case StepRecord::Kind::kTeam:
      if (writer_) recorder_.on_team(record.step, record.team);
      break;
    case StepRecord::Kind::kStep:
      if (writer_) recorder_.after_step(record.step, simulation_->control_table().in_range(record.controls));
      kept_steps_ = record.step;
      break;
    case StepRecord::Kind::kCheckpoint:
      if (writer_) recorder_.checkpoint(record.step, record.state_hash);
      break;
    case StepRecord::Kind::kKeyframe:
      if (writer_) recorder_.keyframe(record.step, loop_->keyframe(record.keyframe_slot));
      loop_->release_keyframe(record.keyframe_slot);
      break;
  }
}

SessionResult Session::finish(SessionEnd end) {
  finished_ = true;
  loop_->stop();
  loop_done_ = true;
  if (keeper_.joinable()) keeper_.join();
  store_notes();
  SessionResult result;
  result.attempt = attempt_;
  result.loop = loop_->stats();
  result.metrics = evaluator_.metrics();  // the loop has stopped: the step thread's evaluator is ours
  result.metrics.team = team_;
  result.score = evaluator_.score(end == SessionEnd::kStoppedByInstructor);
  result.status = records::attempt_status(
      simulation_->diverged(), end == SessionEnd::kInterrupted || !keeper_error_.empty(), result.score);
  std::string kept;
  if (writer_) {
    writer_->finish(recorder_.recording().total_steps);
    kept = io::recording_copy(options_.record, records::kMaxStoredRecordingBytes);
  }
  if (!team_member_[0].empty()) db_->note_team(attempt_, team_member_[0], team_member_[1], team_member_[2]);
  db_->finish_attempt(attempt_, result.metrics, result.score, options_.record, result.status, kept);
  if (!keeper_error_.empty()) throw std::runtime_error("record keeper: " + keeper_error_);
  return result;
}

}  // namespace harbour::station
