#include "harbour/training/Route.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include "harbour/io/DataError.h"
#include "harbour/io/RouteFiles.h"

namespace harbour::training {
namespace {

const std::vector<std::string> kExercises = {HARBOUR_DATA_DIR "/exercises"};

// Every shipped route loads: its exercises by the exercise loader, its bounds on figures they store.
TEST(Routes, EveryShippedRouteLoads) {
  const auto routes = io::load_routes({HARBOUR_DATA_DIR "/routes"}, kExercises);
  ASSERT_EQ(routes.size(), 5u);  // one per machine
  for (const Route& r : routes) {
    EXPECT_GE(r.stages.size(), 2u) << r.id;
    for (const Stage& s : r.stages)
      EXPECT_TRUE(std::filesystem::is_regular_file(s.exercise_file)) << s.id;
  }
  const Route sts = io::load_route(HARBOUR_DATA_DIR "/routes/sts_basic.yaml", kExercises);
  ASSERT_EQ(sts.stages.size(), 5u);
  EXPECT_EQ(sts.stages[0].repetitions, 2);
  EXPECT_TRUE(sts.stages[0].requires_stages.empty());
  EXPECT_EQ(sts.stages[1].requires_stages, std::vector<std::string>{"single_lift"});  // the stage before
  EXPECT_EQ(sts.stages[3].requires_stages, std::vector<std::string>{"single_lift"});  // as it says
  EXPECT_EQ(sts.stages[1].goal, "Discharging a ship");
  EXPECT_EQ(sts.stages[4].exercise, "sts_hoist_brake_fault");  // bounds on the figures a fault stores
  EXPECT_EQ(sts.stages[4].bounds.size(), 3u);
}

std::string route_error(const std::string& text) {
  const auto file = std::filesystem::temp_directory_path() / "harbour_route_test.yaml";
  std::ofstream(file) << text;
  try {
    io::load_route(file.string(), kExercises);
  } catch (const io::DataError& e) {
    return e.what();
  }
  return "(loaded)";
}

const char* const kHead = "name: Test\nmachine: STS\ngoals:\n  - goal: One\n    stages:\n";

// A bad route is refused naming the file, the line and the field.
TEST(Routes, ABadRouteNamesTheFileLineAndField) {
  const std::string cycle = route_error(std::string(kHead) +
                                        "      - {id: a, exercise: sts_discharge, requires: [c]}\n"
                                        "      - {id: b, exercise: sts_discharge}\n"
                                        "      - {id: c, exercise: sts_discharge}\n");
  EXPECT_NE(cycle.find("harbour_route_test.yaml:"), std::string::npos) << cycle;
  EXPECT_NE(cycle.find("a cycle of prerequisites"), std::string::npos) << cycle;
  EXPECT_NE(cycle.find("a -> c -> b -> a"), std::string::npos) << cycle;
  const std::string unknown = route_error(std::string(kHead) + "      - {id: a, exercise: sts_dischrage}\n");
  EXPECT_NE(
      unknown.find("harbour_route_test.yaml:6: goals[0].stages[0].exercise: no exercise 'sts_dischrage'"),
      std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find("sts_discharge"), std::string::npos) << unknown;  // lists the shipped ones
  const std::string metric = route_error(std::string(kHead) +
                                         "      - id: a\n        exercise: sts_discharge\n"
                                         "        pass: {metrics: {spilled_percent: {max: 5}}}\n");
  EXPECT_NE(
      metric.find(":8: goals[0].stages[0].pass.metrics.spilled_percent: exercise 'sts_discharge' stores no "
                  "figure 'spilled_percent'"),
      std::string::npos)
      << metric;
  const std::string missing =
      route_error(std::string(kHead) + "      - {id: a, exercise: sts_discharge, requires: [z]}\n");
  EXPECT_NE(missing.find("no stage 'z' in this route"), std::string::npos) << missing;
  const std::string twice = route_error(std::string(kHead) +
                                        "      - {id: a, exercise: sts_discharge}\n"
                                        "      - {id: a, exercise: sts_discharge}\n");
  EXPECT_NE(twice.find(":7: goals[0].stages[1].id: a second stage 'a'"), std::string::npos) << twice;
  const std::string attempts = route_error(
      std::string(kHead) + "      - {id: a, exercise: sts_discharge, repetitions: 3, max_attempts: 2}\n");
  EXPECT_NE(attempts.find("fewer attempts (2) than repetitions (3)"), std::string::npos) << attempts;
  const std::string typo =
      route_error(std::string(kHead) + "      - {id: a, exercise: sts_discharge, repetitons: 3}\n");
  EXPECT_NE(typo.find("repetitons"), std::string::npos) << typo;
  // the bulk figures are there for a bulk exercise
  EXPECT_EQ(
      route_error(
          std::string(kHead) +
          "      - {id: a, exercise: mhc_coal_discharge, pass: {metrics: {spilled_percent: {max: 5}}}}\n"),
      "(loaded)");
  // a machine's own figures: a tractor stores no twistlock misuse, a reach stacker its limiter trips
  const std::string tractor = route_error(
      std::string(kHead) +
      "      - {id: a, exercise: tractor_mafi_park, pass: {metrics: {twistlock_misuse: {max: 0}}}}\n");
  EXPECT_NE(tractor.find("exercise 'tractor_mafi_park' stores no figure 'twistlock_misuse'"),
            std::string::npos)
      << tractor;
  EXPECT_EQ(
      route_error(
          std::string(kHead) +
          "      - {id: a, exercise: reach_stacker_stack, pass: {metrics: {limiter_trips: {max: 0}}}}\n"),
      "(loaded)");
}

// A centre's own routes stand beside the shipped ones and name the centre's exercises (found before the
// shipped ones) by name; a route file name or a route title the shipped routes use is refused, naming the
// file.
TEST(Routes, ACentresRoutesNameItsOwnExercises) {
  namespace fs = std::filesystem;
  const fs::path centre = fs::temp_directory_path() / ("harbour_centre_" + std::to_string(::getpid()));
  fs::remove_all(centre);
  fs::create_directories(centre / "exercises");
  fs::create_directories(centre / "routes");
  // the centre's own exercise: the shipped single lift, renamed, its machine and vessel where they lie
  std::ifstream shipped(HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  std::string text((std::istreambuf_iterator<char>(shipped)), std::istreambuf_iterator<char>());
  text.replace(text.find("name: sts_discharge"), 19, "name: our_lift");
  for (std::size_t at = 0; (at = text.find("../", at)) != std::string::npos; at += 3)
    text.replace(at, 3, HARBOUR_DATA_DIR "/");
  std::ofstream(centre / "exercises" / "our_lift.yaml") << text;
  std::ofstream(centre / "routes" / "our_basics.yaml")
      << "name: Our basics\nmachine: STS\ngoals:\n  - goal: Lifts\n    stages:\n"
         "      - {id: ours, exercise: our_lift}\n      - {id: theirs, exercise: sts_discharge}\n";
  const std::vector<std::string> exercises = {(centre / "exercises").string(), HARBOUR_DATA_DIR "/exercises"};
  const auto routes = io::load_routes({(centre / "routes").string(), HARBOUR_DATA_DIR "/routes"}, exercises);
  ASSERT_EQ(routes.size(), 6u);
  EXPECT_EQ(routes[0].id, "our_basics");
  EXPECT_EQ(routes[0].stages[0].exercise_file, (centre / "exercises" / "our_lift.yaml").string());
  EXPECT_EQ(routes[0].stages[1].exercise_file, HARBOUR_DATA_DIR "/exercises/sts_discharge.yaml");
  // without the centre's exercise folder the stage names nothing there is
  try {
    io::load_routes({(centre / "routes").string()}, kExercises);
    ADD_FAILURE() << "loaded without the centre's exercises";
  } catch (const io::DataError& e) {
    EXPECT_NE(
        std::string(e.what()).find("our_basics.yaml:6: goals[0].stages[0].exercise: no exercise 'our_lift'"),
        std::string::npos)
        << e.what();
  }
  // a centre's route with a shipped one's title: people pick routes by title, so it is refused
  std::ofstream(centre / "routes" / "our_twin.yaml")
      << "name: STS basic\nmachine: STS\ngoals:\n  - goal: Lifts\n    stages:\n"
         "      - {id: ours, exercise: our_lift}\n";
  try {
    io::load_routes({(centre / "routes").string(), HARBOUR_DATA_DIR "/routes"}, exercises);
    ADD_FAILURE() << "two routes called STS basic";
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.file(), HARBOUR_DATA_DIR "/routes/sts_basic.yaml");
    EXPECT_NE(std::string(e.what()).find("route.name: 'STS basic' is also the name of route 'our_twin'"),
              std::string::npos)
        << e.what();
  }
  fs::remove(centre / "routes" / "our_twin.yaml");
  // a centre's route called as a shipped one
  {
    std::ifstream ours(centre / "routes" / "our_basics.yaml");
    std::string copy((std::istreambuf_iterator<char>(ours)), std::istreambuf_iterator<char>());
    copy.replace(copy.find("Our basics"), 10, "Our copy");
    std::ofstream(centre / "routes" / "sts_basic.yaml") << copy;
  }
  try {
    io::load_routes({(centre / "routes").string(), HARBOUR_DATA_DIR "/routes"}, exercises);
    ADD_FAILURE() << "two routes sts_basic";
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.file(), (centre / "routes" / "sts_basic.yaml").string());
    EXPECT_NE(std::string(e.what()).find("route 'sts_basic' is also"), std::string::npos) << e.what();
  }
  fs::remove_all(centre);
}

Stage stage(const std::string& id, std::vector<std::string> requires_stages = {}, int repetitions = 1,
            int max_attempts = 3) {
  Stage s;
  s.id = id;
  s.exercise = "x";
  s.min_score = 70.0;
  s.bounds = {{"collisions", std::nullopt, 0.0}};
  s.repetitions = repetitions;
  s.max_attempts = max_attempts;
  s.requires_stages = std::move(requires_stages);
  return s;
}

StageAttempt attempt(const std::string& stage, double score, double collisions,
                     const std::string& status = "finished") {
  return {stage, status, score, score >= 70.0, {{"collisions", collisions}}};
}

// Passes are attempts meeting the score and every bound; a stage opens when the ones it requires are passed,
// blocks after its attempts, and an instructor's decision signs it off or grants another round.
TEST(RouteProgress, FollowsTheAttemptsAndTheInstructorsDecisions) {
  Route route;
  route.stages = {stage("a", {}, 2), stage("b", {"a"}), stage("c", {"a"})};
  RouteProgress p = progress(route, {}, {});
  EXPECT_EQ(p.stages[0].state, StageState::kOpen);
  EXPECT_EQ(p.stages[1].state, StageState::kLocked);
  EXPECT_EQ(p.stages[1].missing, std::vector<std::string>{"a"});
  EXPECT_EQ(p.next, "a");

  // one good attempt of two; a high score with a collision is no pass; a running one does not count yet
  std::vector<StageAttempt> attempts = {attempt("a", 95, 0), attempt("a", 90, 1),
                                        attempt("a", 99, 0, "running")};
  p = progress(route, attempts, {});
  EXPECT_EQ(p.stages[0].passes, 1);
  EXPECT_EQ(p.stages[0].attempts, 2);
  EXPECT_EQ(p.stages[0].best_score, 95.0);
  EXPECT_EQ(p.stages[0].state, StageState::kOpen);
  std::string why;
  EXPECT_FALSE(meets(route.stages[0], attempts[1], &why));
  EXPECT_EQ(why, "collisions 1 over 0");

  attempts.back().status = "finished";  // the second pass: b and c open, b first
  p = progress(route, attempts, {});
  EXPECT_EQ(p.stages[0].state, StageState::kPassed);
  EXPECT_EQ(p.stages[1].state, StageState::kOpen);
  EXPECT_EQ(p.next, "b");

  // three failed attempts at b (an interrupted one counts, a diverged one is the physics'): blocked, c next
  for (const char* status : {"finished", "interrupted", "diverged", "finished"})
    attempts.push_back(attempt("b", 40, 0, status));
  p = progress(route, attempts, {});
  EXPECT_EQ(p.stages[1].attempts, 3);
  EXPECT_EQ(p.stages[1].state, StageState::kBlocked);
  EXPECT_EQ(p.next, "c");
  attempts.push_back(attempt("c", 80, 0));
  p = progress(route, attempts, {});
  EXPECT_FALSE(p.next.has_value());
  EXPECT_FALSE(p.complete);

  // the instructor grants another round: b is open with 6 attempts allowed, then signs it off
  std::vector<Override> decisions = {{"b", "retry", "ill that day", "ines", ""}};
  p = progress(route, attempts, decisions);
  EXPECT_EQ(p.stages[1].attempts_allowed, 6);
  EXPECT_EQ(p.next, "b");
  decisions.push_back({"b", "sign_off", "passed on the real crane", "ines", ""});
  p = progress(route, attempts, decisions);
  EXPECT_TRUE(p.stages[1].signed_off);
  EXPECT_TRUE(p.complete);
}

// Without a score of its own a stage takes the exercise's pass mark; an unmeasured figure is no pass.
TEST(RouteProgress, TheExercisesPassMarkAndUnmeasuredFigures) {
  Stage s = stage("a");
  s.min_score.reset();
  StageAttempt a = attempt("a", 65, 0);
  a.passed = true;  // the exercise's own pass mark was lower
  EXPECT_TRUE(meets(s, a));
  a.metrics.clear();
  std::string why;
  EXPECT_FALSE(meets(s, a, &why));
  EXPECT_EQ(why, "collisions not measured");
}

// The percentile rank of a value among a cohort's: below it, plus half the ties (worked by hand).
TEST(Cohort, PercentileRankCountsHalfTheTies) {
  const std::vector<double> best = {55, 70, 70, 85, 100};
  EXPECT_DOUBLE_EQ(percentile_rank(best, 70), 100.0 * (1 + 0.5 * 2) / 5);  // 40
  EXPECT_DOUBLE_EQ(percentile_rank(best, 100), 90.0);
  EXPECT_DOUBLE_EQ(percentile_rank(best, 40), 0.0);
  EXPECT_DOUBLE_EQ(percentile_rank({}, 40), 100.0);
}

}  // namespace
}  // namespace harbour::training
