// What an attempt's result says when the instructor steps in: an attempt passes only with its goals met
// (or, in a fault exercise, its own procedure followed); one the instructor disrupts (a fault, an emergency
// stop, a power failure the exercise does not script) or stops with goals left is ended by the instructor,
// neither passed nor failed. On the STS and the RTG, each with its scripted operator.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Pilot.h"

namespace harbour::sim {
namespace {

struct Timed {
  double at_s;
  InstructorCommand::Kind kind;
};

struct Attempt {
  Metrics metrics;
  Score score;            // as the exercise ends it (or as it stands at `until_s`)
  Score score_stopped;    // the instructor stopping it there
  bool finished = false;  // the exercise ended itself
};

// The scripted operator runs `exercise` with the instructor's commands, until the exercise ends it or
// `until_s`.
Attempt attempt(const char* exercise_name, const std::vector<Timed>& commands, double until_s) {
  const ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/" + exercise_name + ".yaml");
  Simulation simulation(exercise.scenario);
  const std::unique_ptr<Pilot> pilot = make_pilot(exercise);
  Evaluator evaluator(exercise);
  std::size_t next = 0;
  while (!evaluator.finished() && simulation.time_s() < until_s) {
    for (; next < commands.size() && commands[next].at_s <= simulation.time_s(); ++next) {
      InstructorCommand c;
      c.kind = commands[next].kind;
      simulation.command(c);
    }
    const scene::Controls in = pilot->next(simulation);
    simulation.step(in);
    evaluator.observe(simulation, in);
  }
  EXPECT_EQ(simulation.warnings().total(), 0u);
  return {evaluator.metrics(), evaluator.score(), evaluator.score(true), evaluator.finished()};
}

using K = InstructorCommand::Kind;

class InstructorOn : public testing::TestWithParam<const char*> {};

TEST_P(InstructorOn, AFaultTheExerciseDoesNotScriptEndsItByTheInstructorNotAsAPass) {
  // the operator follows the procedure (the load down, the machine stopped): the exercise ends there
  const Attempt a = attempt(GetParam(), {{20.0, K::kHoistBrakeFault}}, 400.0);
  ASSERT_TRUE(a.finished) << "after " << a.metrics.time_s << " s";
  EXPECT_TRUE(a.metrics.stopped_after_fault);
  EXPECT_EQ(a.metrics.instructor_disruptions, 1);
  EXPECT_LT(a.metrics.moves_completed, 1);
  EXPECT_EQ(a.score.outcome, Outcome::kEndedByInstructor) << outcome_name(a.score.outcome);
  EXPECT_FALSE(a.score.passed);
}

TEST_P(InstructorOn, AnEmergencyStopOrAPowerFailureWithGoalsLeftIsNeitherPassNorFail) {
  for (const K kind : {K::kEmergencyStop, K::kPowerFailure}) {
    SCOPED_TRACE(kind == K::kEmergencyStop ? "emergency stop" : "power failure");
    const Attempt a = attempt(GetParam(), {{10.0, kind}}, 25.0);
    EXPECT_FALSE(a.finished);
    EXPECT_EQ(a.metrics.instructor_disruptions, 1);
    EXPECT_EQ(a.score.outcome, Outcome::kEndedByInstructor) << outcome_name(a.score.outcome);
    EXPECT_EQ(a.score_stopped.outcome, Outcome::kEndedByInstructor);
    EXPECT_FALSE(a.score.passed || a.score_stopped.passed);
  }
}

TEST_P(InstructorOn, StoppedWithGoalsLeftItIsTheInstructorsEndWithoutItTheTraineesFail) {
  const Attempt a = attempt(GetParam(), {}, 15.0);
  EXPECT_EQ(a.metrics.instructor_disruptions, 0);
  EXPECT_EQ(a.score_stopped.outcome, Outcome::kEndedByInstructor);  // the instructor's stop
  EXPECT_EQ(a.score.outcome, Outcome::kFailed);                     // out of time: the trainee's
}

TEST_P(InstructorOn, AnOutageLiftedInTimeStillLetsTheGoalsBeMetAndPass) {
  // (not during the RTG's first gantry travel: its scripted operator then misses the box for ever)
  const Attempt a = attempt(GetParam(), {{25.0, K::kPowerFailure}, {28.0, K::kPowerRestored}}, 600.0);
  ASSERT_TRUE(a.finished) << "after " << a.metrics.time_s << " s";
  EXPECT_EQ(a.metrics.instructor_disruptions, 1);
  EXPECT_EQ(a.score.outcome, Outcome::kPassed) << a.score.total;
}

INSTANTIATE_TEST_SUITE_P(Cranes, InstructorOn, testing::Values("sts_discharge", "rtg_rehandle"));

TEST(Outcome, AFaultExercisesOwnProcedureStillPasses) {
  const Attempt a = attempt("sts_hoist_brake_fault", {}, 400.0);
  ASSERT_TRUE(a.finished);
  EXPECT_TRUE(a.metrics.stopped_after_fault);
  EXPECT_EQ(a.metrics.instructor_disruptions, 0);  // the exercise's own fault
  EXPECT_EQ(a.score.outcome, Outcome::kPassed);
}

}  // namespace
}  // namespace harbour::sim
