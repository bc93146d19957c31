// A signaller's hand signals on the STS: they move nothing, and the evaluator times the operator's answer at
// the controls (the time from each signal to the levers following it; a stop followed late costs points).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/scene/HandSignals.h"
#include "harbour/sim/Evaluation.h"

namespace harbour::sim {
namespace {

struct Lever {
  double from_s;
  const char* control;
  double value;
};
struct Given {
  double at_s;
  const char* signal;
};

struct Signalled {
  Metrics metrics;
  Score score;
  std::uint64_t hash = 0;
};

// The STS from rest for `until_s`, its levers set at the times given, the signals given at theirs
Signalled run(const std::vector<Lever>& levers, const std::vector<Given>& signals, double until_s) {
  const ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/sts_discharge.yaml");
  Simulation simulation(exercise.scenario);
  Evaluator evaluator(exercise);
  scene::Controls controls = simulation.control_table().neutral();
  std::size_t next_lever = 0, next_signal = 0;
  while (simulation.time_s() < until_s - 1e-9) {
    for (; next_lever < levers.size() && levers[next_lever].from_s <= simulation.time_s() + 1e-9;
         ++next_lever)
      controls.value[static_cast<std::size_t>(simulation.control_table().find(levers[next_lever].control))] =
          levers[next_lever].value;
    for (; next_signal < signals.size() && signals[next_signal].at_s <= simulation.time_s() + 1e-9;
         ++next_signal) {
      InstructorCommand c;
      c.kind = InstructorCommand::Kind::kSignal;
      c.value = scene::find_hand_signal(signals[next_signal].signal);
      EXPECT_EQ(simulation.why_refused(c), "");
      simulation.command(c);
    }
    simulation.step(controls);
    evaluator.observe(simulation, controls);
  }
  return {evaluator.metrics(), evaluator.score(true), simulation.state_hash()};
}

const std::vector<Lever> kLevers = {
    {3.3, "hoist", 0.4},       // 1.3 s after "hoist"
    {9.0, "hoist", 0.0},       // 4.0 s after "stop": late
    {10.0, "hoist", 0.8},      // "hoist slowly" answered at full speed first,
    {11.5, "hoist", 0.3},      // then slowly: 1.5 s
    {14.0, "trolley", -0.5}};  // "trolley out" answered the wrong way, never followed

TEST(Signals, TheTimeFromEachSignalToTheLeversFollowingItIsMeasuredAndAStopFollowedLateCosts) {
  const Signalled r =
      run(kLevers, {{2.0, "hoist"}, {5.0, "stop"}, {10.0, "hoist-slowly"}, {14.0, "trolley-out"}}, 18.0);
  EXPECT_EQ(r.metrics.signals, 4);
  ASSERT_EQ(r.metrics.signal_delays_s.size(), 3u);
  EXPECT_NEAR(r.metrics.signal_delays_s[0], 1.3, 2e-3);
  EXPECT_NEAR(r.metrics.signal_delays_s[1], 4.0, 2e-3);
  EXPECT_NEAR(r.metrics.signal_delays_s[2], 1.5, 2e-3);
  EXPECT_EQ(r.metrics.late_signals, 2);  // the stop, and the trolley never moved its way
  EXPECT_EQ(r.metrics.late_stop_signals, 1);
  bool deducted = false;
  for (const Score::Deduction& d : r.score.deductions)
    if (d.reason == "stop signal followed late") {
      deducted = true;
      EXPECT_EQ(d.count, 1);
      EXPECT_DOUBLE_EQ(d.points, ExerciseSettings{}.rules.points_late_stop_signal);
      EXPECT_EQ(d.skill, Skill::kSafety);
    }
  EXPECT_TRUE(deducted);
  // the records' figures name them
  bool worst = false;
  for (const auto& [name, value] : r.metrics.rows())
    if (name == "worst_signal_delay_s") {
      worst = true;
      EXPECT_NEAR(value, 4.0, 2e-3);
    }
  EXPECT_TRUE(worst);
}

TEST(Signals, ASignalMovesNothingAndOneTheCraneCannotFollowIsRefused) {
  const Signalled signalled = run(kLevers, {{2.0, "hoist"}, {5.0, "stop"}, {10.0, "lower"}}, 12.0);
  const Signalled quiet = run(kLevers, {}, 12.0);
  EXPECT_EQ(signalled.hash, quiet.hash);
  EXPECT_EQ(quiet.metrics.signals, 0);
  const ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/sts_discharge.yaml");
  Simulation simulation(exercise.scenario);
  InstructorCommand c;
  c.kind = InstructorCommand::Kind::kSignal;
  c.value = scene::find_hand_signal("slew-left");
  EXPECT_NE(simulation.why_refused(c).find("slew"), std::string::npos) << simulation.why_refused(c);
  c.value = static_cast<double>(scene::hand_signals().size());
  EXPECT_NE(why_invalid(c), "");
  c.value = 0.5;
  EXPECT_NE(why_invalid(c), "");
}

}  // namespace
}  // namespace harbour::sim
