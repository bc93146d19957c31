#include "harbour/records/HeadlessRun.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <csignal>

#include "harbour/core/Text.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/records/CentreRoutes.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/sim/Pilot.h"
#include "harbour/sim/Recording.h"
#include "harbour/training/Figures.h"

namespace harbour::records {
namespace {

constexpr double kProgressEvery_s = 10.0;

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// Ctrl-C or a termination request: the run stops between steps and stores the attempt as interrupted
volatile std::sig_atomic_t g_stop_requested = 0;
extern "C" void request_stop(int) {
  g_stop_requested = 1;
}

/// Stops the run on SIGINT/SIGTERM while alive (restoring the default handlers after).
struct StopOnSignal {
  StopOnSignal() {
    g_stop_requested = 0;
    std::signal(SIGINT, request_stop);
    std::signal(SIGTERM, request_stop);
  }
  ~StopOnSignal() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  }
};

// the instructor's commands in time order, each with its text (checked before the run starts)
struct Scheduled {
  io::TimedCommand timed;
  std::string text;
};
std::vector<Scheduled> schedule(const std::vector<std::string>& texts) {
  std::vector<Scheduled> commands;
  for (const std::string& text : texts)
    commands.push_back({io::parse_instructor_command(text), text});
  std::stable_sort(commands.begin(), commands.end(),
                   [](const Scheduled& a, const Scheduled& b) { return a.timed.at_s < b.timed.at_s; });
  return commands;
}

// the exercise's goal and how far it is, in words
std::string goal_text(const sim::ExerciseSettings& exercise) {
  char text[96];
  if (exercise.deliver)
    std::snprintf(text, sizeof text, "deliver %.0f t", exercise.deliver->tonnes);
  else
    std::snprintf(text, sizeof text, "%zu move(s)", exercise.moves.size());
  return text;
}
std::string progress_text(const sim::ExerciseSettings& exercise, const sim::Metrics& metrics) {
  char text[96];
  if (exercise.deliver)
    std::snprintf(text, sizeof text, "delivered %5.1f/%.0f t", metrics.delivered_t, exercise.deliver->tonnes);
  else
    std::snprintf(text, sizeof text, "moves %d/%zu", metrics.moves_completed, exercise.moves.size());
  return text;
}

}  // namespace

// everything a run writes is checked before it starts: a bad output never costs a whole exercise
void check_outputs(const RunOptions& options) {
  if (!options.record.empty())
    if (const std::string why = io::why_not_writable(options.record); !why.empty())
      throw std::runtime_error("--record " + core::printable(options.record) + ": " + why);
  if (const std::string why = core::why_bad_name(options.trainee, 64); !why.empty())
    throw std::runtime_error("--trainee '" + core::printable(options.trainee, 64) + "' " + why);
}

void print_evaluation(const sim::Metrics& m, const sim::Score& s) {
  std::printf("\nevaluation\n");
  // every figure the records store of it (what its machine measures), in words, in the order people read them
  std::vector<std::pair<std::string, double>> rows = m.rows();
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return training::figure_order(a.first) < training::figure_order(b.first);
  });
  for (const auto& [name, value] : rows) {
    const training::FigureWords words = training::figure_words(name);
    std::printf("  %-32s %s\n", words.label.c_str(), training::figure_text(words, value).c_str());
  }
  // and what each move, landing and bite was
  for (std::size_t n = 0; n < m.cycle_times_s.size(); ++n)
    std::printf("  move %zu: cycle time %.1f s\n", n + 1, m.cycle_times_s[n]);
  for (std::size_t n = 0; n < m.placement_offset_m.size(); ++n)
    std::printf("  move %zu placed %.2f m off its mark%s\n", n + 1, m.placement_offset_m[n],
                n < m.placement_skew_deg.size()
                    ? (", " + fixed(m.placement_skew_deg[n], 2) + " deg skew").c_str()
                    : "");
  for (std::size_t n = 0; n < m.landing_sway_m.size(); ++n)
    std::printf("  landing %zu: sway %.3f m\n", n + 1, m.landing_sway_m[n]);
  for (std::size_t n = 0; n < m.bite_fill.size(); ++n)
    std::printf("  bite %zu: %.0f %% full, swing at release %.2f m\n", n + 1, 100.0 * m.bite_fill[n],
                n < m.release_swing_m.size() ? m.release_swing_m[n] : 0.0);
  if (m.collisions > 0)
    std::printf("  collisions by kind: box %d, cell guide %d, ship %d, vehicle %d, other %d\n",
                m.container_collisions, m.cell_guide_collisions, m.ship_collisions, m.vehicle_collisions,
                m.other_collisions);
  if (m.hoist_fault) {
    const std::string set_down = m.fault_set_down_s >= 0.0
                                     ? "load set down " + fixed(m.fault_set_down_s, 1) + " s after it came"
                                     : std::string("no load hung when it came");
    std::printf("  hoist brake fault: %s, %d lifts under the fault, crane %s\n", set_down.c_str(),
                m.lifts_under_fault, m.stopped_after_fault ? "stopped" : "not stopped");
  }
  static constexpr const char* kVerdicts[] = {"PASSED", "NOT PASSED",
                                              "ENDED BY THE INSTRUCTOR (neither passed nor failed)"};
  std::printf("score %.0f / 100: %s\n", s.total, kVerdicts[static_cast<int>(s.outcome)]);
  for (const auto& d : s.deductions)
    std::printf("  -%.0f  %s x%d (%s)\n", d.points, d.reason.c_str(), d.count, sim::skill_name(d.skill));
  std::printf("skills: safety %.0f, precision %.0f, productivity %.0f\n", s.skills[0], s.skills[1],
              s.skills[2]);
}

int drive_attempt(const sim::ExerciseSettings& exercise, sim::Simulation& simulation, sim::Pilot& pilot,
                  sim::Evaluator& evaluator, sim::Recorder& recorder, records::RecordsStore& db,
                  std::optional<std::int64_t> parent, std::int64_t branch_step, const RunOptions& options);

int run_exercise(const RunOptions& options) {
  if (!options.autopilot) {
    std::fprintf(stderr, "harboursim: no input device support yet; run with --autopilot\n");
    return 2;
  }
  check_outputs(options);
  schedule(options.commands);  // a bad command stops the run before it starts
  records::RecordsStore db(options.database.empty() ? records::default_database() : options.database);
  RunOptions run = options;
  std::string exercise_file;
  if (!options.route.empty()) {
    const records::RouteStage next =
        records::next_route_stage(db, options.centre, options.trainee, options.route);
    run.stage = next.stage.id;
    exercise_file = next.stage.exercise_file;
    std::printf("harboursim: route %s, stage %s (%s)\n", next.route.id.c_str(), next.stage.id.c_str(),
                next.stage.goal.c_str());
  } else {
    exercise_file = records::resolve_exercise(options.exercise, options.centre.exercises);
  }
  run.source = io::read_exercise_source(exercise_file);
  const sim::ExerciseSettings exercise = io::load_exercise_source(run.source);
  if (const std::string why = sim::why_no_pilot(exercise); !why.empty())
    throw std::runtime_error(exercise.name + ": " + why);
  sim::Simulation simulation(exercise.scenario);
  const std::unique_ptr<sim::Pilot> pilot = sim::make_pilot(exercise);
  sim::Evaluator evaluator(exercise);
  sim::Recorder recorder(exercise.name, simulation.control_table());
  std::printf("harboursim: exercise %s on the %s, %s, autopilot, time limit %.0f s\n", exercise.name.c_str(),
              simulation.machine().kind(), goal_text(exercise).c_str(), exercise.rules.time_limit_s);
  return drive_attempt(exercise, simulation, *pilot, evaluator, recorder, db, std::nullopt, 0, run);
}

int drive(const sim::ExerciseSettings& exercise, sim::Simulation& simulation, sim::Pilot& pilot,
          sim::Evaluator& evaluator, sim::Recorder& recorder, records::RecordsStore& db, std::int64_t attempt,
          const RunOptions& options, std::optional<io::RecordingWriter>& writer);

// Runs an attempt to its end: the exercise done, its time limit and overtime past, the physics diverged, or
// Ctrl-C. The recording streams as it goes and the attempt is stored with how it ended; an error on the way
// (a full disk, a lost database) still marks the attempt interrupted where it can.
int drive_attempt(const sim::ExerciseSettings& exercise, sim::Simulation& simulation, sim::Pilot& pilot,
                  sim::Evaluator& evaluator, sim::Recorder& recorder, records::RecordsStore& db,
                  std::optional<std::int64_t> parent, std::int64_t branch_step, const RunOptions& options) {
  if (options.trainee == "autopilot") db.ensure_trainee("autopilot", "Scripted operator");
  if (!db.has_trainee(options.trainee))
    throw std::runtime_error("no trainee '" + core::printable(options.trainee) +
                             "' (add it with: harboursim trainees add)");
  std::optional<io::RecordingWriter> writer;
  if (!options.record.empty()) {
    writer.emplace(options.record, recorder.recording());
    recorder.set_sink(&*writer);
  }
  const std::int64_t attempt =
      db.begin_attempt({options.trainee, exercise.name, parent, branch_step, options.record, options.route,
                        options.stage, options.source.version, options.source, options.autopilot});
  std::printf("attempt %lld of trainee %s%s\n", static_cast<long long>(attempt), options.trainee.c_str(),
              options.record.empty() ? "" : (", recording " + options.record).c_str());
  for (int n = 0; n < evaluator.metrics().moves_completed; ++n)  // a take-over's moves before the branch
    db.record_move(attempt, n + 1, evaluator.metrics().time_s,
                   evaluator.metrics().cycle_times_s[static_cast<std::size_t>(n)]);
  try {
    return drive(exercise, simulation, pilot, evaluator, recorder, db, attempt, options, writer);
  } catch (...) {
    try {
      db.finish_attempt(attempt, evaluator.metrics(), evaluator.score(), options.record, "interrupted");
    } catch (...) {  // the database itself failed: the next opening marks the attempt interrupted
    }
    throw;
  }
}

int drive(const sim::ExerciseSettings& exercise, sim::Simulation& simulation, sim::Pilot& pilot,
          sim::Evaluator& evaluator, sim::Recorder& recorder, records::RecordsStore& db, std::int64_t attempt,
          const RunOptions& options, std::optional<io::RecordingWriter>& writer) {
  const StopOnSignal stop_on_signal;
  const auto wall_start = std::chrono::steady_clock::now();
  const double start_s = simulation.time_s();
  double next_progress = start_s + kProgressEvery_s;
  const std::vector<Scheduled> commands = schedule(options.commands);
  // the exercise bounds its run: past its time limit and the overtime its rules allow, it stops
  const double stop_at_s = exercise.rules.time_limit_s + exercise.rules.overtime_s;
  std::size_t next_command = 0;
  sim::Progress stored = sim::progress(evaluator.metrics());  // what the records hold of this attempt
  while (!evaluator.finished() && !simulation.diverged() && !g_stop_requested &&
         simulation.time_s() < stop_at_s) {
    for (; next_command < commands.size() && commands[next_command].timed.at_s <= simulation.time_s();
         ++next_command) {
      simulation.command(commands[next_command].timed.command);
      recorder.on_command(simulation, commands[next_command].timed.command);
      std::printf("  t=%6.1f s  instructor: %s\n", simulation.time_s(), commands[next_command].text.c_str());
    }
    const scene::Controls in = pilot.next(simulation);
    simulation.step(in);
    evaluator.observe(simulation, in);
    if (const sim::Progress now = sim::progress(evaluator.metrics()); now.grew_since(stored)) {
      records::record_progress(db, attempt, stored, now);
      stored = now;
    }
    if (!options.record.empty()) recorder.after_step(simulation, in);
    if (simulation.time_s() >= next_progress) {
      next_progress += kProgressEvery_s;
      if (evaluator.metrics().vehicle) {
        const core::Vec3 v = simulation.world().linear_velocity(simulation.machine().cab_body());
        std::printf("  t=%6.1f s  speed %5.1f km/h  %s  %s\n", simulation.time_s(),
                    std::hypot(v.x, v.y) * 3.6, progress_text(exercise, evaluator.metrics()).c_str(),
                    pilot.activity());
      } else {
        std::printf("  t=%6.1f s  %s z %6.2f m  %s  %s\n", simulation.time_s(),
                    simulation.machine().held_item() ? "load" : "attachment",
                    simulation.machine().attachment_bottom_z_m(),
                    progress_text(exercise, evaluator.metrics()).c_str(), pilot.activity());
      }
      std::fflush(stdout);
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::printf("\nsimulated %.1f s in %.2f s (%.0fx real time), %u physics warnings\n",
              simulation.time_s() - start_s, wall, (simulation.time_s() - start_s) / wall,
              simulation.warnings().total());
  const sim::Score score = evaluator.score();
  const std::string status = records::attempt_status(simulation.diverged(), g_stop_requested != 0, score);
  const bool out_of_time = !simulation.diverged() && !g_stop_requested && !evaluator.finished();
  if (simulation.diverged()) {
    std::printf("STOPPED: the physics diverged at t=%.3f s (%s); the attempt is stored as diverged\n",
                simulation.time_s(), simulation.divergence().c_str());
  } else if (g_stop_requested) {
    std::printf("STOPPED by a signal at t=%.3f s; the attempt is stored as interrupted\n",
                simulation.time_s());
  } else if (out_of_time) {
    std::printf(
        "STOPPED: %.0f s past the time limit of %.0f s (the exercise's overtime) with goals left: %s\n",
        exercise.rules.overtime_s, exercise.rules.time_limit_s,
        progress_text(exercise, evaluator.metrics()).c_str());
  }
  if (score.outcome == sim::Outcome::kEndedByInstructor)
    std::printf(
        "ENDED BY THE INSTRUCTOR: %d instructor disruption%s (a fault, stop or power failure the exercise "
        "does not script) and goals left: neither passed nor failed\n",
        evaluator.metrics().instructor_disruptions,
        evaluator.metrics().instructor_disruptions == 1 ? "" : "s");
  print_evaluation(evaluator.metrics(), score);
  std::string kept;
  if (writer) {
    writer->finish(recorder.recording().total_steps);
    kept = io::recording_copy(options.record, records::kMaxStoredRecordingBytes);
  }
  db.finish_attempt(attempt, evaluator.metrics(), score, options.record, status, kept);
  std::printf("stored as attempt %lld of trainee %s (%s)\n", static_cast<long long>(attempt),
              options.trainee.c_str(), status.c_str());
  if (!options.record.empty()) {
    std::printf("recording %s (%zu input changes, %zu checkpoints)\n", options.record.c_str(),
                recorder.recording().inputs.size(), recorder.recording().checkpoints.size());
  }
  if (simulation.diverged()) return 3;
  if (g_stop_requested) return 130;
  if (out_of_time && score.outcome != sim::Outcome::kEndedByInstructor) return kExitOutOfTime;
  return simulation.warnings().total() == 0 ? 0 : 1;
}

namespace {
int replay_checked(const std::string& recording_path, const sim::Recording& recording,
                   const sim::ExerciseSettings& exercise);
}  // namespace

int replay_recording(const std::string& recording_path, const std::string& exercise_path) {
  return replay_checked(recording_path, io::read_recording(recording_path),
                        records::load_resolved_exercise(records::resolve_exercise(exercise_path)));
}

int replay_attempt(std::int64_t attempt, const std::string& database, const std::string& centre_exercises) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  const std::optional<records::AttemptRow> row = db.attempt(attempt);
  if (!row) {
    std::fprintf(stderr, "harboursim: no attempt %lld in the records\n", static_cast<long long>(attempt));
    return 2;
  }
  if (row->recording.empty()) {
    std::fprintf(stderr, "harboursim: attempt %lld was not recorded\n", static_cast<long long>(attempt));
    return 2;
  }
  std::printf("attempt %lld of trainee %s: %s (%s)\n", static_cast<long long>(attempt), row->trainee.c_str(),
              row->recording.c_str(), db.recording(attempt) ? "the records' copy" : "its file");
  const sim::Recording recording = db.read_recording_of(*row);
  std::string inexact;
  const io::ExerciseSource source = records::attempt_exercise(db, *row, centre_exercises, inexact);
  std::printf("exercise %s version %s (%s)\n", row->exercise.c_str(), source.version.c_str(),
              source.file.c_str());
  if (!inexact.empty()) std::printf("NOTE: %s\n", inexact.c_str());
  return replay_checked(row->recording, recording, io::load_exercise_source(source));
}

namespace {
int replay_checked(const std::string& recording_path, const sim::Recording& recording,
                   const sim::ExerciseSettings& exercise) {
  if (recording.scenario != exercise.name) {
    std::fprintf(stderr, "harboursim: %s was recorded on exercise '%s', not '%s'\n", recording_path.c_str(),
                 recording.scenario.c_str(), exercise.name.c_str());
    return 2;
  }
  // re-simulate with the evaluator watching, checking the recorded hash every second
  sim::Evaluator evaluator(exercise);
  const sim::ReplayResult r =
      sim::replay(exercise.scenario, recording, -1,
                  [&](const sim::Simulation& s, const scene::Controls& in) { evaluator.observe(s, in); });
  if (r.first_mismatch) {
    std::fprintf(stderr,
                 "harboursim: replay diverged at t=%.3f s (recorded with a different build or data?)\n",
                 static_cast<double>(*r.first_mismatch) * sim::Simulation::kStep_s);
    return 1;
  }
  std::printf("replayed %s: %.1f s, %d of %zu recorded seconds reproduced bit for bit%s\n",
              recording_path.c_str(), r.simulation->time_s(), r.checkpoints_checked,
              recording.checkpoints.size(),
              recording.complete ? "" : " (an incomplete recording: its run was interrupted there)");
  if (!recording.team.empty()) {  // what the team's other stations made happen, by kind
    int count[sim::TeamInput::kKinds] = {};
    for (const sim::Recording::TeamEvent& e : recording.team)
      ++count[static_cast<int>(e.input.kind)];
    std::printf(
        "team inputs: %zu (team trucks moved %d, boxes taken over %d, loads handed on %d, obstacles moved "
        "%d)\n",
        recording.team.size(), count[0], count[1], count[2], count[3]);
  }
  print_evaluation(evaluator.metrics(), evaluator.score());
  return 0;
}
}  // namespace

int take_over_recording(const std::string& recording_path, const RunOptions& given, double at_s) {
  const sim::Recording recording = io::read_recording(recording_path);
  RunOptions options = given;
  options.source =
      io::read_exercise_source(records::resolve_exercise(options.exercise, options.centre.exercises));
  const sim::ExerciseSettings exercise = io::load_exercise_source(options.source);
  if (recording.scenario != exercise.name) {
    std::fprintf(stderr, "harboursim: %s was recorded on exercise '%s', not '%s'\n", recording_path.c_str(),
                 recording.scenario.c_str(), exercise.name.c_str());
    return 2;
  }
  const auto step = static_cast<std::int64_t>(std::llround(at_s / sim::Simulation::kStep_s));
  if (step < 0 || step > recording.total_steps) {
    std::fprintf(stderr, "harboursim: --take-over %.3f s is outside the recording (0 to %.3f s)\n", at_s,
                 static_cast<double>(recording.total_steps) * sim::Simulation::kStep_s);
    return 2;
  }
  check_outputs(options);
  schedule(options.commands);
  // the branch's evaluation includes what the original attempt did up to the take-over
  sim::Evaluator evaluator(exercise);
  sim::TakeOver branch =
      sim::take_over(exercise.scenario, recording, recording_path, step,
                     [&](const sim::Simulation& s, const scene::Controls& in) { evaluator.observe(s, in); });
  records::RecordsStore db(options.database.empty() ? records::default_database() : options.database);
  std::optional<std::int64_t> parent;
  if (const std::optional<records::AttemptRow> original = db.attempt_recorded_at(recording_path))
    parent = original->id;
  std::printf("harboursim: took over %s at t=%.3f s (%s)%s; the autopilot drives on\n",
              recording_path.c_str(), branch.simulation->time_s(),
              progress_text(exercise, evaluator.metrics()).c_str(),
              parent ? (", branch of attempt " + std::to_string(*parent)).c_str() : "");
  const std::unique_ptr<sim::Pilot> pilot = sim::make_pilot(exercise);
  pilot->resume(*branch.simulation, evaluator.metrics().moves_completed, branch.levers);
  return drive_attempt(exercise, *branch.simulation, *pilot, evaluator, branch.recorder, db, parent, step,
                       options);
}

}  // namespace harbour::records
