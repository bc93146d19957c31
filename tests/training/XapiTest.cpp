// The xAPI statements of an attempt, built from facts chosen by hand.
#include <gtest/gtest.h>

#include "harbour/training/Xapi.h"

namespace harbour::training::xapi {
namespace {

TEST(Xapi, DurationsAndIrisAreWrittenAsTheSpecificationsSay) {
  EXPECT_EQ(duration(88.625), "PT88.62S");  // hundredths, as ISO 8601 allows a decimal fraction of seconds
  EXPECT_EQ(duration(0.0), "PT0.00S");
  EXPECT_EQ(duration(-3.0), "PT0.00S");
  EXPECT_EQ(iri_segment("sts_discharge"), "sts_discharge");
  EXPECT_EQ(iri_segment("bay 12/hold?x=1"), "bay%2012%2Fhold%3Fx%3D1");
}

TEST(Xapi, AFailedAttemptSaysFailedWithItsScoreAndAnInterruptedOneTerminates) {
  AttemptFacts f;
  f.attempt = 7;
  f.trainee = "t\"01";
  f.exercise = "sts_discharge";
  f.status = "finished";
  f.score = 55.0;
  f.passed = false;
  f.duration_s = 120.0;
  f.metrics = {{"collisions", 3.0}};
  ASSERT_EQ(statements_at_end(f), 2);
  const std::vector<Statement> end = at_end(f, "2026-11-25T10:00:00.000Z", {"a", "b"});
  EXPECT_EQ(end[0].verb, "failed");
  EXPECT_EQ(end[1].verb, "completed");
  EXPECT_NE(end[0].json.find("\"scaled\":0.55"), std::string::npos) << end[0].json;
  EXPECT_NE(end[0].json.find("\"success\":false"), std::string::npos);
  EXPECT_NE(end[0].json.find("\"name\":\"t\\\"01\""), std::string::npos) << "the id escaped as JSON";
  EXPECT_NE(end[0].json.find("\"https://harboursim.org/xapi/extensions/attempt\":7"), std::string::npos);
  EXPECT_EQ(end[0].json.find("contextActivities"), std::string::npos) << "no route: no parent activity";
  f.status = "interrupted";
  ASSERT_EQ(statements_at_end(f), 1);
  const std::vector<Statement> cut = at_end(f, "2026-11-25T10:00:00.000Z", {"c"});
  EXPECT_EQ(cut[0].verb, "terminated");
  EXPECT_EQ(cut[0].json.find("\"score\""), std::string::npos);
  EXPECT_THROW(at_end(f, "2026-11-25T10:00:00.000Z", {}), std::invalid_argument);
}

}  // namespace
}  // namespace harbour::training::xapi
