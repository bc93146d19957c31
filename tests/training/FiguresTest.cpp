#include <gtest/gtest.h>

#include "harbour/sim/Evaluation.h"
#include "harbour/training/Cohort.h"
#include "harbour/training/Figures.h"
#include "harbour/training/Report.h"

namespace harbour::training {
namespace {

// every figure an attempt can store: every optional group of sim::Metrics::rows() switched on
std::vector<std::string> every_stored_figure() {
  sim::Metrics m;
  m.hoist_fault = true;
  m.fault_set_down_s = 12.0;
  m.instructor_disruptions = 1;
  m.vehicle = true;
  m.bulk = true;
  m.trim = true;
  m.placement_offset_m = {0.1};
  m.placement_skew_deg = {0.5};
  m.smoothness = {{"hoist", 0.1, 1}, {"slew", 0.2, 0}};
  m.team = sim::TeamFigures{1, 0, 3.5, 2, 17.0, 40.0};
  std::vector<std::string> names = {"score", "skill_safety", "skill_precision", "skill_productivity"};
  for (const auto& [name, value] : m.rows())
    names.push_back(name);
  return names;
}

TEST(Figures, EveryFigureAnAttemptStoresHasItsOwnWordsInTheTable) {
  const std::vector<std::string> names = every_stored_figure();
  ASSERT_GT(names.size(), 50u);
  for (const std::string& name : names) {
    EXPECT_LT(figure_order(name), figure_table().size()) << name << " is not in the figure table";
    const FigureWords w = figure_words(name);
    EXPECT_EQ(w.label.find('_'), std::string::npos) << name << ": '" << w.label << "'";
    EXPECT_EQ(w.label.find('{'), std::string::npos) << name << ": '" << w.label << "'";
    EXPECT_FALSE(w.about.empty()) << name;
  }
}

TEST(Figures, AValueReadsInItsUnitWithSensibleDigits) {
  EXPECT_EQ(figure_text("hoist_energy_j", 6595334.650145048), "6.6 MJ");
  EXPECT_EQ(figure_text("time_s", 13.6234), "13.6 s");
  EXPECT_EQ(figure_text("time_s", 412.7), "413 s");
  EXPECT_EQ(figure_text("collisions", 3), "3");
  EXPECT_EQ(figure_text("worst_placement_offset_m", 0.0734), "7.34 cm");
  EXPECT_EQ(figure_text("mean_bite_fill", 0.873), "87.3%");
  EXPECT_EQ(figure_text("worst_landing_mps", 0.00007), "0 m/s");  // nothing below a thousandth
  EXPECT_EQ(figure_text("score", 85.0), "85");
  EXPECT_EQ(figure_words("trolley_harsh_moves").label, "trolley harsh moves");
  EXPECT_EQ(figure_words("gantry_rms_jerk_mps3").label, "gantry jerk (RMS)");
  // a name the table does not know: words from the name, its unit from the suffix
  EXPECT_EQ(figure_words("boom_angle_rad").label, "boom angle");
  EXPECT_EQ(figure_text("boom_angle_rad", 1.0), "57.3°");
}

TEST(Figures, WhichWayIsBetterComesFromTheTable) {
  EXPECT_TRUE(higher_is_better("score"));
  EXPECT_TRUE(higher_is_better("skill_safety"));
  EXPECT_TRUE(higher_is_better("tonnes_per_hour"));
  EXPECT_FALSE(higher_is_better("time_s"));
  EXPECT_FALSE(higher_is_better("slew_harsh_moves"));
  EXPECT_FALSE(higher_is_better("collisions"));
}

TEST(Figures, AnEventReadsInWords) {
  EXPECT_EQ(event_text("hard_landing", 0.41), "hard landing at 0.41 m/s");
  EXPECT_EQ(event_text("collision", 0.0), "collision");
  EXPECT_EQ(event_text("speeding", 7.24), "speeding worst so far 7.24 km/h over");
  EXPECT_EQ(event_text("instructor hoist-brake-fault", 0.0), "instructor: hoist brake fault");
  EXPECT_EQ(event_text("device_lost", 0.0), "control device lost");
  EXPECT_EQ(event_text("something_new", 0.0), "something new");
  EXPECT_EQ(event_text("move_done", 2.0), "move 2 done");
  EXPECT_EQ(event_text("attempt_end", 80.0, "ended_by_instructor"),
            "attempt ended by the instructor, score 80");
}

TEST(Figures, TheTraineeReportNamesEachStandingsFigureInWords) {
  TraineeReportData d;
  d.trainee = "ana";
  d.name = "Ana";
  d.generated_at = "2026-11-28";
  AttemptFigures a;
  a.id = 1;
  a.trainee = "ana";
  a.exercise = "sts_discharge";
  a.exercise_version = "0123456789";
  a.status = "finished";
  a.score = 90.0;
  a.passed = true;
  a.metrics = {{"time_s", 95.25}, {"hoist_energy_j", 2.5e6}};
  d.attempts = {a};
  d.standings = standings(d.attempts, "ana");
  const std::string html = trainee_report_html(d);
  EXPECT_NE(html.find("<td>hoist energy</td>"), std::string::npos);
  EXPECT_NE(html.find("2.5 MJ"), std::string::npos);
  EXPECT_EQ(html.find("hoist_energy_j"), std::string::npos);
  EXPECT_EQ(html.find(">time_s<"), std::string::npos);
}

}  // namespace
}  // namespace harbour::training
