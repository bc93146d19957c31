// The xAPI statements of an attempt, built from facts chosen by hand.
#include <gtest/gtest.h>

#include "harbour/training/Xapi.h"

#include <nlohmann/json.hpp>

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

// Two centres sharing an LRS: the same attempt's statement leaves each under the centre's IRIs, with the
// exercise's title and a registration of its own, the vocabulary (verbs, extensions) unchanged.
TEST(Xapi, AStatementLeavesUnderItsCentresIrisWithItsAttemptsRegistration) {
  AttemptFacts f;
  f.attempt = 12;
  f.trainee = "ana";
  f.exercise = "sts_discharge";
  f.route = "sts_basic";
  f.stage = "single_lift";
  const std::vector<Statement> start = at_start(f, "2026-11-28T10:00:00.000Z", {"a", "b"});
  Centre north{"https://north.example/sim",
               {{"sts_discharge", {"First discharge onto a truck", "Take one box."}}}};
  Centre south{"https://south.example/sim", {}};
  const nlohmann::json n = nlohmann::json::parse(addressed(start[0].json, north));
  const nlohmann::json n2 = nlohmann::json::parse(addressed(start[1].json, north));
  const nlohmann::json s = nlohmann::json::parse(addressed(start[0].json, south));
  EXPECT_EQ(n["actor"]["account"]["homePage"], "https://north.example/sim/trainees");
  EXPECT_EQ(s["actor"]["account"]["homePage"], "https://south.example/sim/trainees");
  EXPECT_EQ(n["object"]["id"], "https://north.example/sim/exercises/sts_discharge");
  EXPECT_EQ(n["object"]["definition"]["name"]["en-US"], "First discharge onto a truck");
  EXPECT_EQ(n["object"]["definition"]["description"]["en-US"], "Take one box.");
  EXPECT_EQ(s["object"]["definition"]["name"]["en-US"], "sts_discharge");  // no words known: its name
  EXPECT_EQ(n["context"]["contextActivities"]["parent"][0]["id"],
            "https://north.example/sim/routes/sts_basic/single_lift");
  EXPECT_EQ(n["verb"]["id"], "http://adlnet.gov/expapi/verbs/launched");
  EXPECT_TRUE(n["context"]["extensions"].contains("https://harboursim.org/xapi/extensions/attempt"));
  // one registration per attempt and centre, a UUID (variant bits 10, version 8)
  const std::string r = n["context"]["registration"];
  EXPECT_EQ(r, n2["context"]["registration"]);
  EXPECT_NE(r, s["context"]["registration"]);
  EXPECT_NE(r, registration("https://north.example/sim", 13));
  ASSERT_EQ(r.size(), 36u);
  EXPECT_EQ(r[14], '8');
  EXPECT_NE(std::string("89ab").find(r[19]), std::string::npos) << r;
  EXPECT_EQ(r, registration("https://north.example/sim", 12));
  // a text that is no statement of ours goes as it is
  EXPECT_EQ(addressed("{not json", north), "{not json");
}

}  // namespace
}  // namespace harbour::training::xapi
