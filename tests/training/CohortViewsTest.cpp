// The cohort views and the report pages on attempts whose figures are chosen by hand, so that every
// percentile, slope and plotted point can be worked out on paper.
#include <gtest/gtest.h>

#include "harbour/training/Cohort.h"
#include "harbour/training/Report.h"

namespace harbour::training {
namespace {

AttemptFigures attempt(std::int64_t id, const std::string& trainee, double score, double collisions,
                       const std::string& status = "finished") {
  AttemptFigures a;
  a.id = id;
  a.trainee = trainee;
  a.exercise = "sts_discharge";
  a.exercise_version = "v1";
  a.status = status;
  if (status == "finished") a.score = score;
  a.passed = score >= 70.0;
  a.metrics = {{"collisions", collisions}, {"skill_safety", 100.0 - 10.0 * collisions}};
  return a;
}

// ana: 60, 70, 90, 100 (collisions 2, 1, 0, 0) and one interrupted; ben: 70 (2); cat: 90 (3)
std::vector<AttemptFigures> cohort() {
  return {attempt(1, "ana", 60, 2), attempt(2, "ben", 70, 2),
          attempt(3, "ana", 70, 1), attempt(4, "ana", 0, 0, "interrupted"),
          attempt(5, "ana", 90, 0), attempt(6, "cat", 90, 3),
          attempt(7, "ana", 100, 0)};
}

const Standing* find(const std::vector<Standing>& all, const std::string& figure) {
  for (const Standing& s : all)
    if (s.figure == figure) return &s;
  return nullptr;
}

TEST(CohortViews, StandingsRankTheBestOnEachFigureWithItsDirection) {
  EXPECT_TRUE(higher_is_better("score"));
  EXPECT_TRUE(higher_is_better("moves_per_hour"));
  EXPECT_FALSE(higher_is_better("collisions"));
  EXPECT_FALSE(higher_is_better("time_s"));

  const std::vector<Standing> ana = standings(cohort(), "ana");
  ASSERT_EQ(ana.size(), 3u);
  EXPECT_EQ(ana[0].figure, "score");  // the score first, then the skills, then the rest
  EXPECT_EQ(ana[1].figure, "skill_safety");
  EXPECT_EQ(ana[2].figure, "collisions");
  // bests 100 (ana), 70 (ben), 90 (cat): two below ana's, and hers counts half: 100 x 2.5 / 3
  EXPECT_DOUBLE_EQ(ana[0].best, 100.0);
  EXPECT_EQ(ana[0].trainees, 3);
  EXPECT_NEAR(ana[0].percentile, 100.0 * (2.0 + 0.5) / 3.0, 1e-9);
  // collisions: fewer is better; ana's best 0 against 2 and 3: ahead of both
  EXPECT_DOUBLE_EQ(ana[2].best, 0.0);
  EXPECT_FALSE(ana[2].higher_better);
  EXPECT_NEAR(ana[2].percentile, 100.0 * 2.5 / 3.0, 1e-9);
  // cat: 90 on the score (ben below), 3 collisions (the worst)
  const std::vector<Standing> cat = standings(cohort(), "cat");
  EXPECT_NEAR(find(cat, "score")->percentile, 100.0 * 1.5 / 3.0, 1e-9);
  EXPECT_NEAR(find(cat, "collisions")->percentile, 100.0 * 0.5 / 3.0, 1e-9);
  EXPECT_TRUE(standings(cohort(), "dan").empty());
}

TEST(CohortViews, TheClassOverviewCountsAndFitsTheTrend) {
  const std::vector<TraineeSummary> lines = class_overview(cohort(), {"ana", "ben", "dan"});
  ASSERT_EQ(lines.size(), 3u);
  const TraineeSummary& ana = lines[0];
  EXPECT_EQ(ana.attempts, 5);  // the interrupted one counts as an attempt, not as finished
  EXPECT_EQ(ana.finished, 4);
  EXPECT_EQ(ana.passed, 3);
  EXPECT_EQ(ana.first_score, 60.0);
  EXPECT_EQ(ana.last_score, 100.0);
  EXPECT_EQ(ana.best_score, 100.0);
  EXPECT_NEAR(*ana.recent_score, (70.0 + 90.0 + 100.0) / 3.0, 1e-9);
  EXPECT_NEAR(*ana.recent_skills[0], (90.0 + 100.0 + 100.0) / 3.0, 1e-9);
  EXPECT_FALSE(ana.recent_skills[1].has_value());  // no precision stored
  // scores 60, 70, 90, 100 at 0..3: slope = sum dx dy / sum dx^2 = 70 / 5
  EXPECT_NEAR(*ana.trend, 14.0, 1e-9);
  EXPECT_FALSE(lines[1].trend.has_value());  // one attempt: no slope
  EXPECT_EQ(lines[2].attempts, 0);
  EXPECT_FALSE(lines[2].best_score.has_value());
}

TEST(CohortViews, ComparisonPutsEachBestSideBySide) {
  const std::vector<Compared> c = compare(cohort(), "ana", "dan");
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].figure, "score");
  EXPECT_EQ(c[0].first, 100.0);
  EXPECT_FALSE(c[0].second.has_value());
  const std::vector<Compared> ab = compare(cohort(), "ana", "ben");
  EXPECT_EQ(ab[2].figure, "collisions");
  EXPECT_EQ(ab[2].first, 0.0);
  EXPECT_EQ(ab[2].second, 2.0);
  EXPECT_FALSE(ab[2].higher_better);
}

TEST(Report, PlotsPutEachValueWhereTheAxesSay) {
  // 640 x 200, plot from x 40 to 510, y from 18 (y_max) to 174 (y_min)
  const std::string svg = svg_plot({{"score", "#1f77b4", {0.0, 100.0}}}, 0.0, 100.0, "Score");
  EXPECT_NE(svg.find("points=\"40.0,174.0 510.0,18.0\""), std::string::npos) << svg;
  const std::string middle = svg_plot({{"score", "#1f77b4", {50.0}}}, 0.0, 100.0, "One");
  EXPECT_NE(middle.find("cx=\"275.0\" cy=\"96.0\""), std::string::npos) << middle;  // one attempt: centred
}

TEST(Report, TextFromTheRecordsIsEscaped) {
  EXPECT_EQ(escape_html("<b>\"Tom\" & 'Jerry'</b>"),
            "&lt;b&gt;&quot;Tom&quot; &amp; &#39;Jerry&#39;&lt;/b&gt;");
  TraineeReportData d;
  d.trainee = "x<script>";
  d.name = "<script>alert(1)</script>";
  d.attempts = {attempt(1, "x<script>", 80, 0)};
  const std::string html = trainee_report_html(d);
  EXPECT_EQ(html.find("<script>"), std::string::npos);
  EXPECT_NE(html.find("Trainee report: &lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(html.find("<svg"), std::string::npos);
}

}  // namespace
}  // namespace harbour::training
