// A scripted cohort on a training route: autopilots with the bad-operator defects at three levels run the
// route's stages through the real pipeline (exercise loader, simulation, evaluation, records), and the
// progress read back from the records unlocks, blocks and completes as the attempts say.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/machines/GantryAutopilot.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/training/Cohort.h"
#include "harbour/training/Route.h"

namespace harbour::training {
namespace {

struct Result {
  sim::Metrics metrics;
  sim::Score score;
};

Result run(const std::string& exercise_file, sim::OperatorDefects defects) {
  const sim::ExerciseSettings exercise = io::load_exercise(exercise_file);
  sim::Simulation simulation(exercise.scenario);
  sim::GantryAutopilot pilot(exercise, defects);
  sim::Evaluator evaluator(exercise);
  const double stop_s = exercise.rules.time_limit_s + exercise.rules.overtime_s;
  while (!evaluator.finished() && simulation.time_s() < stop_s) {
    const scene::Controls in = pilot.next(simulation);
    simulation.step(in);
    evaluator.observe(simulation, in);
  }
  return {evaluator.metrics(), evaluator.score()};
}

TEST(Cohort, ProgressOnARouteFollowsWhatTheAttemptsSay) {
  const auto folder = std::filesystem::temp_directory_path() / "harbour_cohort";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "sts_cohort.yaml") << R"(name: STS cohort
machine: STS
goals:
  - goal: A single lift
    stages:
      - id: lift
        exercise: sts_discharge
        pass: {score: 70, metrics: {hard_landings: {max: 0}, twistlock_misuse: {max: 0}}}
        repetitions: 2
        max_attempts: 3
  - goal: Weather
    stages:
      - id: gusty
        exercise: sts_discharge_gusty
        pass: {score: 70, metrics: {sway_landings: {max: 1}}}
)";
  const Route route = io::load_route((folder / "sts_cohort.yaml").string(), {HARBOUR_DATA_DIR "/exercises"});
  const std::string connection = "sqlite3://db=" + (folder / "records.db").string();
  records::RecordsStore db(connection);

  // the defect levels: none; the twistlocks forgotten once; and landing fast as well
  const std::map<std::string, sim::OperatorDefects> cohort = {
      {"level0", {}},
      {"level1", {.forget_lock_once = true}},
      {"level2", {.land_fast = true, .forget_lock_once = true}}};
  std::map<std::string, Result> lift;  // each level's lift, once: the simulation is deterministic
  for (const auto& [trainee, defects] : cohort) {
    db.add_trainee(trainee, "Trainee " + trainee);
    ASSERT_TRUE(db.enrol(trainee, route.id, "ines"));
    lift[trainee] = run(route.stages[0].exercise_file, defects);
  }
  const auto store = [&](const std::string& trainee, const Stage& stage, const Result& r) {
    const auto attempt = db.begin_attempt({trainee, stage.exercise, std::nullopt, 0, "", route.id, stage.id,
                                           io::exercise_version(stage.exercise_file)});
    db.finish_attempt(attempt, r.metrics, r.score, "");
  };
  const auto progress_of = [&](const std::string& trainee) {
    return progress(route, db.stage_attempts(trainee, route.id), db.overrides(trainee, route.id));
  };

  // what the runs measured: the defects show where the evaluation says they do
  EXPECT_EQ(lift["level0"].metrics.hard_landings + lift["level0"].metrics.twistlock_misuse, 0);
  EXPECT_EQ(lift["level1"].metrics.twistlock_misuse, 1);
  EXPECT_EQ(lift["level1"].metrics.hard_landings, 0);
  EXPECT_EQ(lift["level2"].metrics.hard_landings, 1);
  EXPECT_GT(lift["level0"].score.total, lift["level1"].score.total);
  EXPECT_GT(lift["level1"].score.total, lift["level2"].score.total);

  // level 0: one pass leaves the lift open and the weather locked; the second unlocks it; passing it ends
  // the route
  store("level0", route.stages[0], lift["level0"]);
  RouteProgress p = progress_of("level0");
  EXPECT_EQ(p.stages[0].state, StageState::kOpen);
  EXPECT_EQ(p.stages[1].state, StageState::kLocked);
  EXPECT_EQ(p.next, "lift");
  store("level0", route.stages[0], lift["level0"]);
  p = progress_of("level0");
  EXPECT_EQ(p.stages[0].state, StageState::kPassed);
  EXPECT_EQ(p.next, "gusty");
  const Result gusty = run(route.stages[1].exercise_file, {});
  store("level0", route.stages[1], gusty);
  p = progress_of("level0");
  EXPECT_TRUE(p.complete) << "gusty: score " << gusty.score.total << ", sway landings "
                          << gusty.metrics.sway_landings;

  // level 1 passes the score (one twistlock misuse costs 10 points) but not the bound: three attempts and the
  // stage is blocked; the instructor grants another round
  EXPECT_GE(lift["level1"].score.total, 70.0);
  for (int n = 0; n < 3; ++n)
    store("level1", route.stages[0], lift["level1"]);
  p = progress_of("level1");
  EXPECT_EQ(p.stages[0].passes, 0);
  EXPECT_EQ(p.stages[0].attempts, 3);
  EXPECT_EQ(p.stages[0].state, StageState::kBlocked);
  EXPECT_FALSE(p.next.has_value());
  db.add_override("level1", route.id, {"lift", "retry", "talked through the twistlock sequence", "ines", ""});
  p = progress_of("level1");
  EXPECT_EQ(p.next, "lift");
  EXPECT_EQ(p.stages[0].attempts_allowed, 6);

  // level 2: a failed attempt, still open; the best score is the stored one
  store("level2", route.stages[0], lift["level2"]);
  p = progress_of("level2");
  EXPECT_EQ(p.stages[0].state, StageState::kOpen);
  EXPECT_EQ(p.stages[0].best_score, lift["level2"].score.total);
  EXPECT_EQ(p.stages[1].state, StageState::kLocked);

  // the cohort views read back from the records say what the runs measured: on the lift's version the score
  // ranks level0 > level1 > level2, hard landings (fewer is better) put level2 last
  const std::vector<AttemptFigures> stored = db.attempt_figures();
  ASSERT_EQ(stored.size(), 7u);
  const auto standing = [&](const std::string& trainee, const std::string& figure) {
    for (const Standing& s : standings(stored, trainee))
      if (s.exercise == "sts_discharge" && s.figure == figure) return s;
    ADD_FAILURE() << trainee << " has no standing on " << figure;
    return Standing{};
  };
  EXPECT_NEAR(standing("level0", "score").percentile, 100.0 * 2.5 / 3.0, 1e-9);
  EXPECT_NEAR(standing("level1", "score").percentile, 100.0 * 1.5 / 3.0, 1e-9);
  EXPECT_NEAR(standing("level2", "score").percentile, 100.0 * 0.5 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(standing("level2", "hard_landings").best, 1.0);
  EXPECT_NEAR(standing("level2", "hard_landings").percentile, 100.0 * 0.5 / 3.0, 1e-9);
  EXPECT_NEAR(standing("level0", "hard_landings").percentile, 100.0 * (1.0 + 0.5 * 2.0) / 3.0, 1e-9);
  // places: a tie shares the better place and says so (a tie at the top is first, not "percentile 50")
  EXPECT_EQ(standing("level0", "score").place, 1);
  EXPECT_EQ(standing("level0", "score").tied, 0);
  EXPECT_EQ(standing("level2", "score").place, 3);
  EXPECT_EQ(standing("level0", "hard_landings").place, 1);
  EXPECT_EQ(standing("level0", "hard_landings").tied, 1);
  EXPECT_EQ(place_words(1, 3, 1), "1st of 3 (tied)");
  EXPECT_EQ(place_words(2, 12, 0), "2nd of 12");
  EXPECT_EQ(place_words(13, 20, 0), "13th of 20");
  EXPECT_EQ(place_words(23, 30, 0), "23rd of 30");
  EXPECT_EQ(standing("level0", "score").trainees, 3);
  // the evolution plotted for level0 is its three stored scores in order, and the class sees the same
  const std::vector<TraineeSummary> lines = class_overview(stored, {"level0", "level1", "level2"});
  EXPECT_EQ(lines[0].first_score, lift["level0"].score.total);
  EXPECT_EQ(lines[0].last_score, gusty.score.total);
  EXPECT_EQ(lines[1].finished, 3);
  EXPECT_NEAR(*lines[1].trend, 0.0, 1e-12);  // the same run three times
  EXPECT_EQ(lines[2].best_score, lift["level2"].score.total);
}

}  // namespace
}  // namespace harbour::training
