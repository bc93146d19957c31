#include "harbour/records/RecordsStore.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <soci/soci.h>
#include <sys/wait.h>
#include <unistd.h>
#include <regex>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "harbour/machines/GantryAutopilot.h"
#include "scenes/StsScenes.h"
#include "support/PostgresServer.h"

namespace harbour::records {
namespace {

std::string fresh_db(const char* name) {
  const auto path = std::filesystem::temp_directory_path() / name;
  for (const char* suffix : {"", "-wal", "-shm"})
    std::filesystem::remove(path.string() + suffix);
  return "sqlite3://db=" + path.string();
}

// The same tests run on both backends the store takes: an SQLite file and a live PostgreSQL server.
enum class Backend { sqlite3, postgresql };

std::string fresh_connection(Backend backend, const std::string& name) {
  if (backend == Backend::sqlite3) return fresh_db(("harbour_" + name + ".db").c_str());
  static test::PostgresServer server;  // one private server per test process
  return server.create_database(name);
}

class RecordsStoreOn : public ::testing::TestWithParam<Backend> {};

// What opening `connection` throws ("" when it opens).
std::string error_opening(const std::string& connection);

INSTANTIATE_TEST_SUITE_P(Backends, RecordsStoreOn, ::testing::Values(Backend::sqlite3, Backend::postgresql),
                         [](const ::testing::TestParamInfo<Backend>& param_info) {
                           return std::string(param_info.param == Backend::sqlite3 ? "SQLite" : "PostgreSQL");
                         });

TEST_P(RecordsStoreOn, StoresTraineesAttemptsMovesAndScores) {
  RecordsStore db(fresh_connection(GetParam(), "records_roundtrip"));
  db.add_trainee("t001", "Ana Pérez");
  EXPECT_THROW(db.add_trainee("t001", "Again"), std::runtime_error);
  db.rename_trainee("t001", "Ana Pérez Gil");
  EXPECT_EQ(db.trainees().at(0).name, "Ana Pérez Gil");
  EXPECT_THROW(db.rename_trainee("t999", "Nobody"), std::out_of_range);
  EXPECT_THROW(db.rename_trainee("t001", "bad\x1b[31m"), std::invalid_argument);
  EXPECT_EQ(db.trainees().at(0).name, "Ana Pérez Gil");
  // instructors pick trainees by name: a second trainee of the same name (any case) is refused, saying whose
  try {
    db.add_trainee("t002", "ana pérez gil");
    ADD_FAILURE() << "a second Ana Pérez Gil was added";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("is trainee 't001''s"), std::string::npos) << e.what();
  }
  db.add_trainee("t002", "Ana Pérez Ruiz");
  EXPECT_THROW(db.rename_trainee("t002", "ANA Pérez GIL"), std::runtime_error);
  db.rename_trainee("t001", "Ana Pérez Gil");  // its own name again
  EXPECT_THROW(db.begin_attempt("t999", "sts_discharge"), std::runtime_error);
  const auto first = db.begin_attempt("t001", "sts_discharge");
  db.record_move(first, 1, 93.5, 93.5);
  db.record_event(first, 40.0, "hard_landing", 0.45);
  sim::Metrics m;
  m.moves_completed = 1;
  sim::Score s;
  s.total = 95;
  s.passed = true;
  db.finish_attempt(first, m, s, "out/a.hsrc");
  const auto branch = db.begin_attempt("t001", "sts_discharge", first, 7300);  // an instructor's take-over
  const auto rows = db.attempts(std::string("t001"));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].id, branch);
  EXPECT_EQ(rows[0].status, "running");
  EXPECT_EQ(rows[0].parent, first);
  EXPECT_EQ(rows[0].branch_step, 7300);
  EXPECT_EQ(rows[1].status, "finished");
  EXPECT_EQ(rows[1].score, 95.0);
  EXPECT_TRUE(rows[1].passed);
  EXPECT_EQ(rows[1].moves, 1);
  // when each started and ended (UTC, ISO 8601, ordered as text), and who drove (none was the autopilot)
  EXPECT_EQ(rows[1].started_at.size(), 24u) << rows[1].started_at;
  EXPECT_EQ(rows[1].started_at.back(), 'Z');
  EXPECT_LE(rows[1].started_at, rows[1].ended_at);
  EXPECT_LE(rows[1].ended_at, rows[0].started_at);
  EXPECT_EQ(rows[0].ended_at, "");  // still running
  EXPECT_FALSE(rows[0].autopilot || rows[1].autopilot);
  const auto driven = db.begin_attempt({"t001", "sts_discharge", std::nullopt, 0, "", "", "", "", {}, true});
  EXPECT_TRUE(db.attempts(std::string("t001"))[0].autopilot);
  EXPECT_EQ(db.attempts(std::string("t001"))[0].id, driven);
  EXPECT_EQ(db.trainees().size(), 2u);  // t001 and t002: attempts add none
  // the attempt a recording file holds: the branch written over the same file is the newest there
  EXPECT_EQ(db.attempt_recorded_at("out/a.hsrc")->id, first);
  db.finish_attempt(branch, m, s, "out/a.hsrc");
  EXPECT_EQ(db.attempt_recorded_at("out/a.hsrc")->id, branch);
  EXPECT_FALSE(db.attempt_recorded_at("out/none.hsrc").has_value());
}

// The schemas earlier builds made, as they made them: version 1 (the first records) and version 2 (the
// build before this one: attempts name their process; the console's accounts and audit log).
const char* const kSchemaV1[] = {
    "CREATE TABLE trainees (id TEXT PRIMARY KEY, name TEXT NOT NULL)",
    "CREATE TABLE attempts (id BIGINT PRIMARY KEY, trainee TEXT NOT NULL REFERENCES trainees(id), exercise "
    "TEXT "
    "NOT NULL, status TEXT NOT NULL, score DOUBLE PRECISION, passed INTEGER NOT NULL, parent BIGINT, "
    "branch_step "
    "BIGINT NOT NULL, recording TEXT NOT NULL)",
    "CREATE TABLE moves (attempt BIGINT NOT NULL REFERENCES attempts(id), idx INTEGER NOT NULL, "
    "completed_at_s "
    "DOUBLE PRECISION NOT NULL, cycle_time_s DOUBLE PRECISION NOT NULL, PRIMARY KEY (attempt, idx))",
    "CREATE TABLE events (attempt BIGINT NOT NULL REFERENCES attempts(id), at_s DOUBLE PRECISION NOT NULL, "
    "kind "
    "TEXT NOT NULL, value DOUBLE PRECISION NOT NULL)",
    "CREATE TABLE metrics (attempt BIGINT NOT NULL REFERENCES attempts(id), name TEXT NOT NULL, value DOUBLE "
    "PRECISION NOT NULL, PRIMARY KEY (attempt, name))"};
const char* const kSchemaV2[] = {"ALTER TABLE attempts ADD COLUMN process TEXT NOT NULL DEFAULT ''",
                                 "CREATE TABLE accounts (name TEXT PRIMARY KEY, role TEXT NOT NULL, "
                                 "password_hash TEXT NOT NULL, trainee TEXT "
                                 "REFERENCES trainees(id))",
                                 "CREATE TABLE audit (at TEXT NOT NULL, account TEXT NOT NULL, action TEXT "
                                 "NOT NULL, target TEXT NOT NULL, "
                                 "detail TEXT NOT NULL)"};

// a database as the build of schema `version` (1 or 2) left it: a trainee, a finished attempt with a move,
// an event and a metric
void make_old_database(const std::string& connection, int version) {
  soci::session sql(records_connection(connection));
  for (const char* statement : kSchemaV1)
    sql << statement;
  if (version >= 2)
    for (const char* statement : kSchemaV2)
      sql << statement;
  sql << "INSERT INTO trainees (id, name) VALUES ('t001', 'Ana Pérez')";
  sql << "INSERT INTO attempts (id, trainee, exercise, status, score, passed, parent, branch_step, recording)"
         " VALUES (1, 't001', 'sts_discharge', 'finished', 95.0, 1, NULL, 0, 'a.hsrc')";
  sql << "INSERT INTO moves (attempt, idx, completed_at_s, cycle_time_s) VALUES (1, 1, 93.5, 93.5)";
  sql << "INSERT INTO events (attempt, at_s, kind, value) VALUES (1, 40.0, 'hard_landing', 0.45)";
  sql << "INSERT INTO metrics (attempt, name, value) VALUES (1, 'collisions', 0)";
}

// a database made by this build, taken back to schema version 8 (no deductions kept) and 7 (no teams)
void drop_deductions(soci::session& sql) {
  sql << "DROP TABLE deductions";
}
void drop_attempt_team(soci::session& sql) {
  drop_deductions(sql);
  for (const char* column : {"team", "team_role", "team_session"})
    sql << "ALTER TABLE attempts DROP COLUMN " << column;
}
// the columns of versions 7 and 8
void drop_attempt_times(soci::session& sql) {
  drop_attempt_team(sql);
  for (const char* column : {"started_at", "ended_at", "autopilot"})
    sql << "ALTER TABLE attempts DROP COLUMN " << column;
}

// Databases of earlier builds are upgraded in place, their rows kept; the new columns read as empty.
TEST_P(RecordsStoreOn, DatabasesOfEarlierBuildsAreUpgradedInPlace) {
  for (int version : {1, 2}) {
    const std::string connection =
        fresh_connection(GetParam(), "records_upgrade_v" + std::to_string(version));
    make_old_database(connection, version);
    RecordsStore db(connection);
    EXPECT_EQ(db.schema_version(), 9) << "from version " << version;
    const auto rows = db.attempts();
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0].status, "finished");
    EXPECT_EQ(rows[0].score, 95.0);
    EXPECT_EQ(rows[0].moves, 1);
    EXPECT_EQ(rows[0].route, "");
    EXPECT_EQ(rows[0].exercise_version, "");
    EXPECT_EQ(db.events(1).size(), 1u);
    EXPECT_EQ(db.metrics(1).size(), 1u);
    EXPECT_EQ(db.begin_attempt(
                  {"t001", "sts_discharge", std::nullopt, 0, "", "sts_basic", "single_lift", "abc", {}}),
              2);
    EXPECT_TRUE(db.enrol("t001", "sts_basic", "ines"));
    EXPECT_EQ(db.attempts()[0].stage, "single_lift");
    RecordsStore again(connection);  // opening an upgraded database changes nothing
    EXPECT_EQ(again.attempts().size(), 2u);
  }
  // a version-2 database of the builds before the console: no accounts, no audit log
  const std::string connection = fresh_connection(GetParam(), "records_upgrade_v2_no_console");
  make_old_database(connection, 2);
  {
    soci::session sql(records_connection(connection));
    sql << "DROP TABLE audit";
    sql << "DROP TABLE accounts";
  }
  RecordsStore db(connection);
  EXPECT_EQ(db.account_count(), 0);
  db.audit("ines", "login", "", "");
  EXPECT_EQ(db.audit_log(5).size(), 1u);

  // a version-3 database (routes, no xAPI outbox) gets the outbox; its attempts keep no statements
  const std::string v3 = fresh_connection(GetParam(), "records_upgrade_v3");
  {
    RecordsStore made(v3);
    made.add_trainee("t001", "Ana");
    made.begin_attempt("t001", "sts_discharge");
    soci::session sql(records_connection(v3));
    sql << "DROP TABLE exercise_versions";
    sql << "DROP TABLE recordings";
    sql << "DROP TABLE xapi_outbox";
    drop_attempt_times(sql);
    sql << "UPDATE schema_version SET version = 3";
  }
  RecordsStore upgraded(v3);
  EXPECT_EQ(upgraded.schema_version(), 9);
  EXPECT_TRUE(upgraded.xapi_outbox().empty());
  EXPECT_EQ(upgraded.attempts().size(), 1u);

  // a version-4 database (no recordings kept) gets the table; its attempts have no copy
  const std::string v4 = fresh_connection(GetParam(), "records_upgrade_v4");
  {
    RecordsStore made(v4);
    made.add_trainee("t001", "Ana");
    made.finish_attempt(made.begin_attempt("t001", "sts_discharge"), {}, {}, "/recordings/a.hsrc");
    soci::session sql(records_connection(v4));
    sql << "DROP TABLE exercise_versions";
    sql << "DROP TABLE recordings";
    drop_attempt_times(sql);
    sql << "UPDATE schema_version SET version = 4";
  }
  RecordsStore upgraded_v4(v4);
  EXPECT_EQ(upgraded_v4.schema_version(), 9);
  EXPECT_FALSE(upgraded_v4.recording(1).has_value());
  EXPECT_EQ(upgraded_v4.attempts()[0].recording, "/recordings/a.hsrc");

  // a version-5 database (no exercise versions kept) gets the table; its attempts' versions have no copy
  const std::string v5 = fresh_connection(GetParam(), "records_upgrade_v5");
  {
    RecordsStore made(v5);
    made.add_trainee("t001", "Ana");
    made.begin_attempt({"t001", "sts_discharge", std::nullopt, 0, "", "", "", "0123456789abcdef", {}});
    soci::session sql(records_connection(v5));
    sql << "DROP TABLE exercise_versions";
    drop_attempt_times(sql);
    sql << "UPDATE schema_version SET version = 5";
  }
  RecordsStore upgraded_v5(v5);
  EXPECT_EQ(upgraded_v5.schema_version(), 9);
  EXPECT_FALSE(upgraded_v5.kept_exercise("0123456789abcdef").has_value());

  // a version-6 database (no attempt times) gets the columns: its attempts read no times and no autopilot
  const std::string v6 = fresh_connection(GetParam(), "records_upgrade_v6");
  {
    RecordsStore made(v6);
    made.add_trainee("t001", "Ana");
    made.begin_attempt({"t001", "sts_discharge", std::nullopt, 0, "", "", "", "", {}, true});
    soci::session sql(records_connection(v6));
    drop_attempt_times(sql);
    sql << "UPDATE schema_version SET version = 6";
  }
  RecordsStore upgraded_v6(v6);
  EXPECT_EQ(upgraded_v6.schema_version(), 9);
  ASSERT_EQ(upgraded_v6.attempts().size(), 1u);
  EXPECT_EQ(upgraded_v6.attempts()[0].started_at, "");
  EXPECT_FALSE(upgraded_v6.attempts()[0].autopilot);

  // a version-7 database (no teams) gets the columns: its attempts were no team's
  const std::string v7 = fresh_connection(GetParam(), "records_upgrade_v7");
  {
    RecordsStore made(v7);
    made.add_trainee("t001", "Ana");
    made.begin_attempt({"t001", "sts_discharge", std::nullopt, 0, "", "", "", "", {}, true});
    soci::session sql(records_connection(v7));
    drop_attempt_team(sql);
    sql << "UPDATE schema_version SET version = 7";
  }
  RecordsStore upgraded_v7(v7);
  EXPECT_EQ(upgraded_v7.schema_version(), 9);
  ASSERT_EQ(upgraded_v7.attempts().size(), 1u);
  EXPECT_EQ(upgraded_v7.attempts()[0].team, "");
  EXPECT_TRUE(upgraded_v7.attempts()[0].autopilot);
  upgraded_v7.note_team(1, "sts_and_tractor", "crane", "sts_and_tractor@2026-11-27T20:31:52Z");
  EXPECT_EQ(upgraded_v7.attempts()[0].team, "sts_and_tractor");
  EXPECT_EQ(upgraded_v7.attempts()[0].team_role, "crane");
  EXPECT_EQ(upgraded_v7.attempts()[0].team_session, "sts_and_tractor@2026-11-27T20:31:52Z");
  // a session's members found together, oldest first; an attempt of no session is in none
  upgraded_v7.begin_attempt({"t001", "tractor_mafi_park", std::nullopt, 0, "", "", "", "", {}, true});
  upgraded_v7.begin_attempt({"t001", "sts_discharge", std::nullopt, 0, "", "", "", "", {}, true});
  upgraded_v7.note_team(2, "sts_and_tractor", "tractor", "sts_and_tractor@2026-11-27T20:31:52Z");
  const std::vector<AttemptRow> session =
      upgraded_v7.session_attempts("sts_and_tractor@2026-11-27T20:31:52Z");
  ASSERT_EQ(session.size(), 2u);
  EXPECT_EQ(session[0].team_role, "crane");
  EXPECT_EQ(session[1].team_role, "tractor");
  EXPECT_TRUE(upgraded_v7.session_attempts("sts_and_tractor@2026-11-27T20:31:53Z").empty());
  EXPECT_TRUE(upgraded_v7.session_attempts("").empty());

  // a version-8 database gets the deductions table; its attempts have none kept, a new one keeps its own
  const std::string v8 = fresh_connection(GetParam(), "records_upgrade_v8");
  {
    RecordsStore made(v8);
    made.add_trainee("t001", "Ana");
    made.begin_attempt({"t001", "sts_discharge", std::nullopt, 0, "", "", "", "", {}, false});
    soci::session sql(records_connection(v8));
    drop_deductions(sql);
    sql << "UPDATE schema_version SET version = 8";
  }
  RecordsStore upgraded_v8(v8);
  EXPECT_EQ(upgraded_v8.schema_version(), 9);
  EXPECT_TRUE(upgraded_v8.deductions(1).empty());
  sim::Score score;
  score.total = 65.0;
  score.deductions = {{"collision", 2, 20.0, sim::Skill::kSafety},
                      {"hard landing", 3, 15.0, sim::Skill::kPrecision}};
  upgraded_v8.finish_attempt(1, sim::Metrics{}, score, "", "finished");
  const std::vector<DeductionRow> kept = upgraded_v8.deductions(1);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].reason, "collision");
  EXPECT_EQ(kept[0].skill, "safety");
  EXPECT_EQ(kept[0].count, 2);
  EXPECT_EQ(kept[0].points, 20.0);
  EXPECT_EQ(kept[1].reason, "hard landing");
  EXPECT_EQ(kept[1].skill, "precision");
}

// Every exercise version an attempt ran is kept once, by its content hash, with the folder its paths resolve
// from; a kept text that no longer hashes to its version is an error naming it.
TEST_P(RecordsStoreOn, TheExerciseVersionAnAttemptRanIsKept) {
  const std::string connection = fresh_connection(GetParam(), "records_exercise_versions");
  RecordsStore db(connection);
  db.add_trainee("t001", "Ana");
  io::ExerciseSource source;
  source.file = "/centre/exercises/drill.yaml";
  source.folder = "/centre/exercises";
  source.text = "exercise:\n  name: drill  # \u00e9t\u00e9, every byte kept\n";
  source.version = io::exercise_text_version(source.text);
  for (int n = 0; n < 2; ++n)  // two attempts of one version: kept once
    db.begin_attempt({"t001", "drill", std::nullopt, 0, "", "", "", source.version, source});
  const std::optional<io::ExerciseSource> kept = db.kept_exercise(source.version);
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->text, source.text);
  EXPECT_EQ(kept->folder, source.folder);
  EXPECT_EQ(kept->version, source.version);
  EXPECT_FALSE(db.kept_exercise("ffffffffffffffff"));
  soci::session(records_connection(connection)) << "UPDATE exercise_versions SET text = 'exercise: {}'";
  try {
    db.kept_exercise(source.version);
    FAIL() << "a damaged copy was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("drill version " + source.version + " is damaged"),
              std::string::npos)
        << e.what();
  }
}

// A finished attempt keeps its recording's bytes with it, whatever they are, so that a console or station
// elsewhere replays it; a damaged copy is an error naming the attempt; one past the limit stays a file only.
TEST_P(RecordsStoreOn, AFinishedAttemptKeepsItsRecording) {
  const std::string connection = fresh_connection(GetParam(), "records_recordings");
  RecordsStore db(connection);
  db.add_trainee("t001", "Ana");
  std::string bytes = "HSRC";
  for (int k = 0; k < 300000; ++k)
    bytes.push_back(
        static_cast<char>(static_cast<unsigned>(k) * 7919u % 256u));  // every byte value, zeros among them
  const std::int64_t kept = db.begin_attempt("t001", "sts_discharge");
  db.finish_attempt(kept, {}, {}, "/elsewhere/kept.hsrc", "finished", bytes);
  const std::int64_t none = db.begin_attempt("t001", "sts_discharge");
  db.finish_attempt(none, {}, {}, "/elsewhere/none.hsrc", "interrupted");
  const std::int64_t huge = db.begin_attempt("t001", "sts_discharge");
  db.finish_attempt(huge, {}, {}, "/elsewhere/huge.hsrc", "finished",
                    std::string(kMaxStoredRecordingBytes + 1, 'x'));
  EXPECT_EQ(db.recording(kept), bytes);
  EXPECT_FALSE(db.recording(none).has_value());
  EXPECT_FALSE(db.recording(huge).has_value()) << "past the limit: its file only";
  EXPECT_EQ(db.attempts().size(), 3u);

  // a copy changed behind the store's back
  soci::session(records_connection(connection))
      << "UPDATE recordings SET data = 'not base64!' WHERE attempt = " << kept;
  std::string error;
  try {
    db.recording(kept);
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("recording of attempt " + std::to_string(kept) + " is damaged"), std::string::npos)
      << error;
}

// Each attempt queues its xAPI statements in the transaction that begins or ends it; the outbox hands out
// what is due, keeps failures with their error until their next try, and never again what was sent or
// rejected.
TEST_P(RecordsStoreOn, AttemptsQueueTheirXapiStatementsWithThem) {
  RecordsStore db(fresh_connection(GetParam(), "records_xapi"));
  db.add_trainee("t001", "Ana Pérez");
  const auto a =
      db.begin_attempt({"t001", "sts_discharge", std::nullopt, 0, "", "sts_basic", "single_lift", "v1"});
  std::vector<XapiRow> out = db.xapi_outbox();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].verb, "launched");
  EXPECT_EQ(out[1].verb, "attempted");
  const std::regex uuid4("[0-9a-f]{8}-[0-9a-f]{4}-4[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}");
  EXPECT_TRUE(std::regex_match(out[0].statement_id, uuid4)) << out[0].statement_id;
  EXPECT_NE(out[0].statement_id, out[1].statement_id);
  EXPECT_NE(out[0].statement.find("\"name\":\"t001\""), std::string::npos) << out[0].statement;
  EXPECT_NE(out[0].statement.find("/routes/sts_basic/single_lift"), std::string::npos) << out[0].statement;
  sim::Metrics m;
  m.time_s = 88.625;
  m.collisions = 2;
  sim::Score score;
  score.total = 95.0;
  score.passed = true;
  db.finish_attempt(a, m, score, "");
  out = db.xapi_outbox();
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[2].verb, "passed");
  EXPECT_EQ(out[3].verb, "completed");
  for (const char* expected : {"\"scaled\":0.95", "\"raw\":95.0", "\"success\":true",
                               "\"duration\":\"PT88.62S\"", "/metrics/collisions\":2.0"})
    EXPECT_NE(out[2].statement.find(expected), std::string::npos) << expected << " in " << out[2].statement;
  EXPECT_EQ(out[2].statement.find(out[0].statement_id), std::string::npos);
  // an interrupted attempt terminates, incomplete
  const auto b = db.begin_attempt("t001", "sts_discharge");
  db.finish_attempt(b, m, score, "", "interrupted");
  out = db.xapi_outbox();
  ASSERT_EQ(out.size(), 7u);
  EXPECT_EQ(out[6].verb, "terminated");
  EXPECT_NE(out[6].statement.find("\"completion\":false"), std::string::npos) << out[6].statement;

  // the outbox: due in order; a failure waits for its next try; sent and rejected are done
  const std::string now = out[6].queued_at;
  ASSERT_EQ(db.xapi_due(now, 100).size(), 7u);
  EXPECT_EQ(db.xapi_due(now, 3).size(), 3u);
  db.xapi_failed(out[0].id, "connection refused", "2999-01-01T00:00:00.000Z", false);
  db.xapi_sent(out[1].id, now);
  db.xapi_failed(out[2].id, "400: bad statement", now, true);
  const std::vector<XapiRow> due = db.xapi_due(now, 100);
  ASSERT_EQ(due.size(), 4u);
  EXPECT_EQ(due[0].id, out[3].id);
  EXPECT_EQ(db.xapi_due("2999-01-01T00:00:00.000Z", 100).size(), 5u);  // the failed one's time has come
  out = db.xapi_outbox();
  EXPECT_EQ(out[0].tries, 1);
  EXPECT_EQ(out[0].last_error, "connection refused");
  EXPECT_EQ(out[1].state, "sent");
  EXPECT_EQ(out[2].state, "rejected");
  EXPECT_EQ(out[2].last_error, "400: bad statement");
}

// An upgrade that fails half-way (here a table of version 3 is already there, made by something else) is
// rolled back whole: the database stays at version 2 with its rows, and the error says which step failed.
TEST_P(RecordsStoreOn, AFailedUpgradeLeavesTheDatabaseAsItWas) {
  const std::string connection = fresh_connection(GetParam(), "records_upgrade_fails");
  make_old_database(connection, 2);
  soci::session(records_connection(connection)) << "CREATE TABLE route_overrides (x INTEGER)";
  std::string error;
  try {
    RecordsStore db(connection);
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("from schema version 2 to 3"), std::string::npos) << error;
  EXPECT_NE(error.find("nothing was changed"), std::string::npos) << error;
  soci::session sql(records_connection(connection));
  std::string route;
  bool has_route = true;
  try {
    sql << "SELECT route FROM attempts", soci::into(route);
  } catch (const soci::soci_error&) {
    has_route = false;
  }
  EXPECT_FALSE(has_route) << "the first step of the upgrade stayed";
  int attempts = 0;
  sql << "SELECT COUNT(*) FROM attempts", soci::into(attempts);
  EXPECT_EQ(attempts, 1);
  // with the stray table gone the upgrade goes through
  sql << "DROP TABLE route_overrides";
  RecordsStore db(connection);
  EXPECT_EQ(db.schema_version(), 9);
}

// A database a newer build has upgraded is refused, not read wrongly or downgraded.
TEST(RecordsStore, ADatabaseOfANewerBuildIsRefused) {
  const std::string connection = fresh_db("harbour_newer.db");
  { RecordsStore db(connection); }
  soci::session(records_connection(connection)) << "UPDATE schema_version SET version = 10";
  const std::string error = error_opening(connection);
  EXPECT_NE(error.find("schema version 10 was made by a newer harboursim"), std::string::npos) << error;
}

// Enrolments, an instructor's decisions and the attempts at a route's stages with their metrics.
TEST_P(RecordsStoreOn, StoresEnrolmentsDecisionsAndStageAttempts) {
  RecordsStore db(fresh_connection(GetParam(), "records_routes"));
  db.add_trainee("t001", "Ana Pérez");
  EXPECT_THROW(db.enrol("t999", "sts_basic", "ines"), std::out_of_range);
  EXPECT_TRUE(db.enrol("t001", "sts_basic", "ines"));
  EXPECT_FALSE(db.enrol("t001", "sts_basic", "ines"));
  ASSERT_EQ(db.enrolments(std::string("t001")).size(), 1u);
  EXPECT_EQ(db.enrolments()[0].account, "ines");
  EXPECT_THROW(db.add_override("t001", "sts_basic", {"single_lift", "promote", "why", "ines", ""}),
               std::invalid_argument);
  EXPECT_THROW(db.add_override("t001", "sts_basic", {"single_lift", "sign_off", "", "ines", ""}),
               std::invalid_argument);
  EXPECT_THROW(db.add_override("t001", "mhc_bulk", {"hook_lift", "sign_off", "why", "ines", ""}),
               std::out_of_range);
  db.add_override("t001", "sts_basic",
                  {"single_lift", "sign_off", "passed it on the real crane", "ines", ""});
  const auto decisions = db.overrides("t001", "sts_basic");
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_EQ(decisions[0].reason, "passed it on the real crane");
  EXPECT_FALSE(decisions[0].at.empty());
  const auto a =
      db.begin_attempt({"t001", "sts_bay12_deck", std::nullopt, 0, "", "sts_basic", "deck_discharge", "v1"});
  sim::Metrics m;
  m.collisions = 2;
  sim::Score s;
  s.total = 80;
  s.passed = true;
  db.finish_attempt(a, m, s, "");
  db.begin_attempt("t001", "sts_discharge");  // not on the route
  const auto attempts = db.stage_attempts("t001", "sts_basic");
  ASSERT_EQ(attempts.size(), 1u);
  EXPECT_EQ(attempts[0].stage, "deck_discharge");
  EXPECT_EQ(attempts[0].score, 80.0);
  EXPECT_EQ(attempts[0].metrics.at("collisions"), 2.0);
  EXPECT_EQ(attempts[0].metrics.at("skill_safety"), 100.0);
}

TEST(RecordsStore, ABadConnectionNamesIt) {
  try {
    RecordsStore db("sqlite3://db=/nonexistent/dir/records.db");
    FAIL() << "opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/records.db"), std::string::npos) << e.what();
  }
  try {
    RecordsStore db("postgresql://dbname=records host=/nonexistent/socketdir port=5433");
    FAIL() << "opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("host=/nonexistent/socketdir"), std::string::npos) << e.what();
  }
}

std::string error_opening(const std::string& connection) {
  try {
    RecordsStore db(connection);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// Content nobody of ours wrote: refused with the database and the table or row named, nothing written.
TEST(RecordsStore, ADatabaseWrittenBySomethingElseIsRefusedNamingItAndWhere) {
  const auto path = std::filesystem::temp_directory_path() / "harbour_foreign.db";
  const std::string connection = fresh_db("harbour_foreign.db");
  { std::ofstream(path) << "a spreadsheet, not a database\n"; }
  std::string error = error_opening(connection);
  EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  EXPECT_NE(error.find("not a database"), std::string::npos) << error;

  fresh_db("harbour_foreign.db");
  { soci::session(connection) << "CREATE TABLE attempts (id INTEGER, trainee TEXT)"; }
  error = error_opening(connection);
  EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  EXPECT_NE(error.find("table 'attempts' is not the one of schema version 1"), std::string::npos) << error;
  {
    soci::session sql(connection);
    int tables = 0;
    sql << "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = 'attempts'",
        soci::into(tables);
    EXPECT_EQ(tables, 1);
    int columns = 0;
    sql << "SELECT COUNT(*) FROM pragma_table_info('attempts')", soci::into(columns);
    EXPECT_EQ(columns, 2);  // left as it was
  }

  fresh_db("harbour_foreign.db");
  {
    RecordsStore db(connection);
    db.add_trainee("t001", "Ana Pérez");
    db.begin_attempt("t001", "sts_discharge");
    db.begin_attempt("t001", "sts_discharge");
  }
  RecordsStore db(connection);
  for (const char* damage : {"status = 'perhaps'", "passed = 7", "score = 250", "branch_step = -5"}) {
    soci::session(connection) << "UPDATE attempts SET " << damage << " WHERE id = 2";
    try {
      db.attempts();
      ADD_FAILURE() << "read an attempt with " << damage;
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
    EXPECT_NE(error.find(path.string()), std::string::npos) << error;
    EXPECT_NE(error.find("attempt 2"), std::string::npos) << error;
    soci::session(connection) << "UPDATE attempts SET status = 'running', passed = 0, score = NULL, "
                                 "branch_step = 0 WHERE id = 2";
    EXPECT_EQ(db.attempts().size(), 2u);
  }
}

// The console writes to the records while a station is in the middle of writing: it waits for the lock.
TEST(RecordsStore, WritingWhileAnotherConnectionWritesWaitsForIt) {
  const std::string connection = fresh_db("harbour_busy.db");
  { RecordsStore db(connection); }
  soci::session station(connection);
  station << "BEGIN EXCLUSIVE";
  station << "INSERT INTO trainees (id, name) VALUES ('t007', 'Busy')";
  std::thread commit_later([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    station << "COMMIT";
  });
  try {
    RecordsStore console(connection);
    console.add_trainee("t008", "Waiting");  // blocked until the station commits
    commit_later.join();
    EXPECT_EQ(console.trainees().size(), 2u);
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
    commit_later.join();
  }
}

// A station killed mid-exercise: everything measured before the kill is in the database, consistently.
TEST_P(RecordsStoreOn, KillingTheProcessMidExerciseKeepsTheMovesDoneSoFar) {
  const std::string connection = fresh_connection(GetParam(), "records_kill");
  {
    RecordsStore db(connection);
    db.add_trainee("t001", "Ana Pérez");
  }
  sim::ExerciseSettings exercise = scenes::sts_discharge_exercise(HARBOUR_DATA_DIR);
  exercise.moves.push_back({"TGHU1000010", {-5.0, 0.0, 2.591 / 2}, 0.3});  // then a second box onto the quay

  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // the station: run the exercise, storing each move the moment it completes, never finishing
    RecordsStore db(connection);
    const auto attempt = db.begin_attempt("t001", exercise.name);
    sim::Simulation simulation(exercise.scenario);
    sim::GantryAutopilot pilot(exercise);
    sim::Evaluator evaluator(exercise);
    for (int k = 0; k < 600000; ++k) {
      const scene::Controls in = pilot.next(simulation);
      simulation.step(in);
      const int before = evaluator.metrics().moves_completed;
      evaluator.observe(simulation, in);
      if (evaluator.metrics().moves_completed > before)
        db.record_move(attempt, evaluator.metrics().moves_completed, simulation.time_s(),
                       evaluator.metrics().cycle_times_s.back());
    }
    _exit(0);
  }
  // the parent watches the database and kills the station as soon as the first move is stored
  int moves = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (moves == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    RecordsStore watcher(connection);
    const auto rows = watcher.attempts();
    moves = rows.empty() ? 0 : rows[0].moves;
  }
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_EQ(moves, 1) << "the station never stored its first move";

  RecordsStore after(connection);
  const auto rows = after.attempts();
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].status, "interrupted");  // never finished, never half-written; its process is gone
  EXPECT_EQ(rows[0].moves, 1);
}

}  // namespace
}  // namespace harbour::records

namespace harbour::records {
namespace {

// Eight stations of a centre writing at once, each on its own connection: every attempt is stored, with its
// own id, its moves and its final figures; none fails on a lock or on the shared trainee.
TEST_P(RecordsStoreOn, EightConcurrentWritersAllStoreTheirAttempts) {
  const std::string connection = fresh_connection(GetParam(), "records_eight");
  RecordsStore(connection).add_trainee("t001", "Ana Pérez");  // the schema exists before the stations start
  std::vector<std::thread> stations;
  std::vector<std::string> errors(8);
  for (int n = 0; n < 8; ++n)
    stations.emplace_back([&, n] {
      try {
        RecordsStore db(connection);
        db.ensure_trainee("autopilot", "Scripted operator");
        for (int k = 0; k < 3; ++k) {
          const auto attempt = db.begin_attempt(n % 2 ? "t001" : "autopilot", "sts_discharge");
          db.record_move(attempt, 1, 90.0, 90.0);
          db.record_event(attempt, 40.0, "collision", 0.2);
          sim::Metrics m;
          m.moves_completed = 1;
          sim::Score s;
          s.total = 90;
          db.finish_attempt(attempt, m, s, "");
        }
      } catch (const std::exception& e) {
        errors[static_cast<std::size_t>(n)] = e.what();
      }
    });
  for (std::thread& t : stations)
    t.join();
  for (const std::string& e : errors)
    EXPECT_EQ(e, "");
  RecordsStore db(connection);
  const auto rows = db.attempts();
  ASSERT_EQ(rows.size(), 24u);
  for (const AttemptRow& a : rows) {
    EXPECT_EQ(a.status, "finished");
    EXPECT_EQ(a.moves, 1);
  }
}

TEST(RecordsStore, WhatCannotPersistIsRefusedAndAForeignDatabaseIsLeftUntouched) {
  for (const char* connection : {"sqlite3://db=:memory:", "sqlite3://db=", "sqlite3://", "mysql://x"})
    EXPECT_THROW(RecordsStore db(connection), std::runtime_error) << connection;
  // a path with a space persists under its whole name
  const auto spaced = std::filesystem::temp_directory_path() / "harbour records with space.db";
  std::filesystem::remove(spaced);
  RecordsStore(spaced.string()).add_trainee("t001", "Ana");
  EXPECT_TRUE(std::filesystem::exists(spaced));
  EXPECT_EQ(RecordsStore("sqlite3://db=" + spaced.string()).trainees().size(), 1u);
  // someone else's database: refused before a table is created or the journal mode changed
  const auto foreign = std::filesystem::temp_directory_path() / "harbour_foreign.db";
  std::filesystem::remove(foreign);
  soci::session("sqlite3://db=" + foreign.string()) << "CREATE TABLE bookmarks (url TEXT)";
  const auto bytes_before = std::filesystem::file_size(foreign);
  EXPECT_NE(
      error_opening("sqlite3://db=" + foreign.string()).find("table 'bookmarks', which is not harboursim's"),
      std::string::npos);
  EXPECT_EQ(std::filesystem::file_size(foreign), bytes_before);
  EXPECT_FALSE(std::filesystem::exists(foreign.string() + "-wal"));
  int tables = 0;
  soci::session("sqlite3://db=" + foreign.string()) << "SELECT COUNT(*) FROM sqlite_master",
      soci::into(tables);
  EXPECT_EQ(tables, 1);
  // names that would garble a terminal are refused
  RecordsStore db(fresh_db("harbour_names.db"));
  EXPECT_THROW(db.add_trainee("t\x1b[31m", "Ana"), std::invalid_argument);
  EXPECT_THROW(db.add_trainee("t002", std::string("An\0a", 4)), std::invalid_argument);
  EXPECT_THROW(db.add_trainee("t003", std::string(50 << 20, 'a')), std::invalid_argument);
}

}  // namespace
}  // namespace harbour::records
