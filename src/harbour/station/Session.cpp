#include "harbour/station/Session.h"

#include <chrono>
#include <stdexcept>

#include "harbour/core/Text.h"
#include "harbour/io/RecordingFile.h"

namespace harbour::station {

Session::Session(const sim::ExerciseSettings& exercise, const SessionOptions& options)
    : exercise_(exercise),
      options_(options),
      simulation_(std::make_unique<sim::Simulation>(exercise.scenario)),
      shadow_(std::make_unique<sim::Simulation>(exercise.scenario)),
      evaluator_(exercise),
      recorder_(exercise.name, simulation_->control_table()) {
  db_ = std::make_unique<io::RecordsStore>(options.database);
  if (!db_->has_trainee(options.trainee))
    throw std::runtime_error("no trainee '" + options.trainee + "' (add it with: harboursim trainees add)");
  std::optional<std::int64_t> parent;
  std::int64_t branch_step = 0;
  if (options.take_over) {
    // only an attempt the centre's records know is continued: a command names no other file to read
    const std::optional<io::AttemptRow> taken = db_->attempt_recorded_at(options.take_over->recording);
    if (!taken)
      throw std::runtime_error("take-over refused: no stored attempt was recorded at '" +
                               core::printable(options.take_over->recording) + "'");
    parent = taken->id;
    const sim::Recording original = io::read_recording(options.take_over->recording);
    if (original.scenario != exercise.name)
      throw std::runtime_error(options.take_over->recording + " was recorded on exercise '" +
                               original.scenario + "', not '" + exercise.name + "'");
    if (options.take_over->step < 0 || options.take_over->step > original.total_steps)
      throw std::runtime_error("take-over at step " + std::to_string(options.take_over->step) +
                               ": outside the recording (0 to " + std::to_string(original.total_steps) + ")");
    // the evaluation sees the original attempt up to the take-over; the shadow starts from the same state
    sim::TakeOver branch = sim::take_over(
        exercise.scenario, original, options.take_over->recording, options.take_over->step,
        [this](const sim::Simulation& s, const sim::Controls& in) { evaluator_.observe(s, in); });
    simulation_ = std::move(branch.simulation);
    shadow_->restore_state(simulation_->save_state());
    recorder_ = std::move(branch.recorder);
    branch_step = simulation_->steps();
    moves_before_start_ = evaluator_.metrics().moves_completed;
    metrics_ = evaluator_.metrics();
  }
  if (!options.record.empty()) {
    writer_.emplace(options.record, recorder_.recording());
    recorder_.set_sink(&*writer_);
  }
  attempt_ = db_->begin_attempt({options.trainee, exercise.name, parent, branch_step, options.record,
                                 options.route, options.stage, options.exercise_version});
  loop_ = std::make_unique<RealTimeLoop>(*simulation_, options.loop);
  // the exercise bounds the run: its moves done (the keeper says so), or its time and overtime past
  const double stop_at_s = exercise.rules.time_limit_s + exercise.rules.overtime_s;
  loop_->set_stop_when(
      [this, stop_at_s](const sim::Simulation& s) { return over_.load() || s.time_s() >= stop_at_s; });
}

Session::~Session() {
  if (!finished_) {
    try {
      finish(true);
    } catch (...) {  // the database itself failed: its next opening marks the attempt interrupted
    }
  }
}

void Session::start() {
  keeper_ = std::thread([this] { keep(); });
  loop_->start();
}

sim::Metrics Session::metrics() const {
  const std::lock_guard lock(metrics_mutex_);
  return metrics_;
}

sim::Score Session::score() const {
  const std::lock_guard lock(metrics_mutex_);
  return score_;
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
    db_->record_event(attempt_, shadow_->time_s(), kind, value);
}

void Session::keep() {
  try {
    StepRecord record;
    for (;;) {
      store_notes();
      if (loop_->records().pop(record)) {
        keep(record);
        continue;
      }
      if (loop_done_.load()) {
        if (!loop_->records().pop(record)) break;
        keep(record);
        continue;
      }
      // the ring holds 32 s: waking 100 times a second, not 1000, costs a served station 2 % of a core less
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  } catch (const std::exception& e) {
    keeper_error_ = e.what();  // reported by finish(); the loop is told to stop
    over_ = true;
  }
}

void Session::keep(const StepRecord& record) {
  // the attempt ends on the step its goals were met: the steps the live loop ran on before it stopped are
  // neither evaluated (a bulk delivery would go on growing) nor recorded
  if (over_.load()) return;
  switch (record.kind) {
    case StepRecord::Kind::kCommand:
      shadow_->command(record.command);
      recorder_.on_command(*shadow_, record.command);
      break;
    case StepRecord::Kind::kCheckpoint:
      if (shadow_->steps() != record.step || shadow_->state_hash() != record.state_hash) ++hash_mismatches_;
      break;
    case StepRecord::Kind::kStep: {
      shadow_->single_step(record.controls);
      const sim::Metrics before = evaluator_.metrics();
      evaluator_.observe(*shadow_, record.controls);
      io::record_progress(*db_, attempt_, before, evaluator_.metrics());
      if (writer_) recorder_.after_step(*shadow_, record.controls);
      if (shadow_->steps() % 50 == 0 || evaluator_.metrics().moves_completed != before.moves_completed) {
        const std::lock_guard lock(metrics_mutex_);  // for displays: 20 times a simulated second is plenty
        metrics_ = evaluator_.metrics();
        score_ = evaluator_.score();
      }
      if (evaluator_.finished() || shadow_->diverged()) over_ = true;
      break;
    }
  }
}

SessionResult Session::finish(bool interrupted) {
  finished_ = true;
  loop_->stop();
  loop_done_ = true;
  if (keeper_.joinable()) keeper_.join();
  store_notes();
  SessionResult result;
  result.attempt = attempt_;
  result.loop = loop_->stats();
  result.hash_mismatches = hash_mismatches_.load();
  result.metrics = evaluator_.metrics();
  result.score = evaluator_.score();
  result.status = simulation_->diverged()                 ? "diverged"
                  : interrupted || !keeper_error_.empty() ? "interrupted"
                                                          : "finished";
  if (writer_) writer_->finish(recorder_.recording().total_steps);
  db_->finish_attempt(attempt_, result.metrics, result.score, options_.record, result.status);
  if (!keeper_error_.empty()) throw std::runtime_error("record keeper: " + keeper_error_);
  return result;
}

}  // namespace harbour::station
