#include "harbour/records/RecordsStore.h"

#include <tuple>

#include <soci/soci.h>
#include <sodium.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "harbour/core/Text.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/training/Xapi.h"

namespace harbour::records {
namespace {

// setting WAL mode while another station opens the same file: tries, and the wait between them (10 s in all,
// the busy timeout's)
constexpr int kWalAttempts = 200;
constexpr std::chrono::milliseconds kWalRetry{50};

// The schema's versions. 1: the first records (trainees, attempts, moves, events, metrics); 2: attempts
// remember their process, console accounts and the audit log; 3: routes (enrolments, instructors'
// overrides), attempts name their route stage and the exercise version they ran. Databases before version 3
// have no schema_version table: 2 when attempts has the process column, else 1. 4: the xAPI outbox. 5: the
// attempts' recordings, so that a console or a station on another PC replays and continues them. 6: every
// exercise version an attempt ran, by its content hash (a replay re-simulates what the trainee had, whatever
// its file says now), and attempts ended by the instructor. 7: when an attempt started and ended (UTC, ISO
// 8601), and whether the autopilot drove it. 8: a team session's member: its team, its role and the session
// it was part of (the members' attempts linked by it).
constexpr int kSchemaVersion = 9;

// every table of a schema version with the columns this build reads (and, for the latest, writes)
struct TableColumns {
  const char* table;
  const char* columns;
  int since, changed;  // the version that made it, and the last one that changed its columns
};
constexpr TableColumns kTables[] = {
    {"trainees", "id, name", 1, 1},
    {"attempts",
     "id, trainee, exercise, status, score, passed, parent, branch_step, recording, process, route, stage, "
     "exercise_version, started_at, ended_at, autopilot, team, team_role, team_session",
     1, 8},
    {"moves", "attempt, idx, completed_at_s, cycle_time_s", 1, 1},
    {"events", "attempt, at_s, kind, value", 1, 1},
    {"metrics", "attempt, name, value", 1, 1},
    {"accounts", "name, role, password_hash, trainee", 2, 2},
    {"audit", "at, account, action, target, detail", 2, 2},
    {"enrolments", "trainee, route, at, account", 3, 3},
    {"route_overrides", "trainee, route, stage, action, reason, account, at", 3, 3},
    {"schema_version", "version", 3, 3},
    {"xapi_outbox",
     "id, statement_id, attempt, verb, statement, queued_at, state, tries, next_try_at, last_error, sent_at",
     4, 4},
    {"recordings", "attempt, bytes, data", 5, 5},
    {"exercise_versions", "version, exercise, folder, text", 6, 6},
    {"deductions", "attempt, idx, reason, skill, count, points", 9, 9},
};

// the columns `table` had at `version` ("" : not there yet)
std::string columns_at(const TableColumns& t, int version) {
  if (version < t.since) return "";
  if (version >= t.changed) return t.columns;
  // attempts before version 8; before 7 without their times and driver; before 3 without route, stage and
  // version; before 2 without process
  if (version >= 7)
    return "id, trainee, exercise, status, score, passed, parent, branch_step, recording, process, route, "
           "stage, exercise_version, started_at, ended_at, autopilot";
  if (version >= 3)
    return "id, trainee, exercise, status, score, passed, parent, branch_step, recording, process, route, "
           "stage, "
           "exercise_version";
  return version >= 2
             ? "id, trainee, exercise, status, score, passed, parent, branch_step, recording, process"
             : "id, trainee, exercise, status, score, passed, parent, branch_step, recording";
}

// The statements that take a database from version - 1 to version: the portable subset of SQL that SQLite
// and PostgreSQL both accept. Run in one transaction with the version's row.
std::vector<std::string> migration(int version) {
  switch (version) {
    case 1:
      return {
          "CREATE TABLE trainees (id TEXT PRIMARY KEY, name TEXT NOT NULL)",
          "CREATE TABLE attempts (id BIGINT PRIMARY KEY, trainee TEXT NOT NULL REFERENCES trainees(id),"
          " exercise TEXT NOT NULL, status TEXT NOT NULL, score DOUBLE PRECISION, passed INTEGER NOT NULL,"
          " parent BIGINT, branch_step BIGINT NOT NULL, recording TEXT NOT NULL)",
          "CREATE TABLE moves (attempt BIGINT NOT NULL REFERENCES attempts(id), idx INTEGER NOT NULL,"
          " completed_at_s DOUBLE PRECISION NOT NULL, cycle_time_s DOUBLE PRECISION NOT NULL,"
          " PRIMARY KEY (attempt, idx))",
          "CREATE TABLE events (attempt BIGINT NOT NULL REFERENCES attempts(id),"
          " at_s DOUBLE PRECISION NOT NULL, kind TEXT NOT NULL, value DOUBLE PRECISION NOT NULL)",
          "CREATE TABLE metrics (attempt BIGINT NOT NULL REFERENCES attempts(id), name TEXT NOT NULL,"
          " value DOUBLE PRECISION NOT NULL, PRIMARY KEY (attempt, name))"};
    case 2:
      // builds of version 2 made accounts and audit only when the console first ran
      return {
          "ALTER TABLE attempts ADD COLUMN process TEXT NOT NULL DEFAULT ''",
          "CREATE TABLE IF NOT EXISTS accounts (name TEXT PRIMARY KEY, role TEXT NOT NULL,"
          " password_hash TEXT NOT NULL, trainee TEXT REFERENCES trainees(id))",
          "CREATE TABLE IF NOT EXISTS audit (at TEXT NOT NULL, account TEXT NOT NULL, action TEXT NOT NULL,"
          " target TEXT NOT NULL, detail TEXT NOT NULL)"};
    case 3:
      // builds between the process column and the console made version-2 databases without its tables
      return {
          "CREATE TABLE IF NOT EXISTS accounts (name TEXT PRIMARY KEY, role TEXT NOT NULL,"
          " password_hash TEXT NOT NULL, trainee TEXT REFERENCES trainees(id))",
          "CREATE TABLE IF NOT EXISTS audit (at TEXT NOT NULL, account TEXT NOT NULL, action TEXT NOT NULL,"
          " target TEXT NOT NULL, detail TEXT NOT NULL)",
          "ALTER TABLE attempts ADD COLUMN route TEXT NOT NULL DEFAULT ''",
          "ALTER TABLE attempts ADD COLUMN stage TEXT NOT NULL DEFAULT ''",
          "ALTER TABLE attempts ADD COLUMN exercise_version TEXT NOT NULL DEFAULT ''",
          "CREATE TABLE enrolments (trainee TEXT NOT NULL REFERENCES trainees(id), route TEXT NOT NULL,"
          " at TEXT NOT NULL, account TEXT NOT NULL, PRIMARY KEY (trainee, route))",
          "CREATE TABLE route_overrides (trainee TEXT NOT NULL REFERENCES trainees(id), route TEXT NOT NULL,"
          " stage TEXT NOT NULL, action TEXT NOT NULL, reason TEXT NOT NULL, account TEXT NOT NULL,"
          " at TEXT NOT NULL)",
          "CREATE TABLE schema_version (version INTEGER NOT NULL)",
          "INSERT INTO schema_version (version) VALUES (0)"};
    case 4:
      // the attempts' xAPI statements, queued in the transaction that makes them true, until an LRS has them
      return {
          "CREATE TABLE xapi_outbox (id BIGINT PRIMARY KEY, statement_id TEXT NOT NULL UNIQUE,"
          " attempt BIGINT NOT NULL REFERENCES attempts(id), verb TEXT NOT NULL, statement TEXT NOT NULL,"
          " queued_at TEXT NOT NULL, state TEXT NOT NULL, tries INTEGER NOT NULL, next_try_at TEXT NOT NULL,"
          " last_error TEXT NOT NULL, sent_at TEXT NOT NULL)"};
    case 5:
      // a finished attempt's recording file, base64 (a TEXT both databases take whole)
      return {
          "CREATE TABLE recordings (attempt BIGINT PRIMARY KEY REFERENCES attempts(id), bytes BIGINT NOT "
          "NULL,"
          " data TEXT NOT NULL)"};
    case 6:
      // an exercise file's text by its version, as the attempts that name the version ran it
      return {
          "CREATE TABLE exercise_versions (version TEXT PRIMARY KEY, exercise TEXT NOT NULL, folder TEXT NOT "
          "NULL, text TEXT NOT NULL)"};
    case 7:
      // when an attempt started and ended ('' : before), and whether the autopilot drove it
      return {"ALTER TABLE attempts ADD COLUMN started_at TEXT NOT NULL DEFAULT ''",
              "ALTER TABLE attempts ADD COLUMN ended_at TEXT NOT NULL DEFAULT ''",
              "ALTER TABLE attempts ADD COLUMN autopilot INTEGER NOT NULL DEFAULT 0"};
    case 8:
      // a team session's member ('' : alone, or before)
      return {"ALTER TABLE attempts ADD COLUMN team TEXT NOT NULL DEFAULT ''",
              "ALTER TABLE attempts ADD COLUMN team_role TEXT NOT NULL DEFAULT ''",
              "ALTER TABLE attempts ADD COLUMN team_session TEXT NOT NULL DEFAULT ''"};
    case 9:
      // what a finished attempt's score took off and why, in the score's order (none kept before)
      return {
          "CREATE TABLE deductions (attempt BIGINT NOT NULL REFERENCES attempts(id), idx INTEGER NOT NULL,"
          " reason TEXT NOT NULL, skill TEXT NOT NULL, count INTEGER NOT NULL,"
          " points DOUBLE PRECISION NOT NULL, PRIMARY KEY (attempt, idx))"};
    default:
      return {};
  }
}

// a random (version 4) UUID, as xAPI statement ids are
std::string random_uuid() {
  if (sodium_init() < 0) throw std::runtime_error("libsodium could not start (no random numbers)");
  unsigned char b[16];
  randombytes_buf(b, sizeof b);
  b[6] = static_cast<unsigned char>((b[6] & 0x0f) | 0x40);
  b[8] = static_cast<unsigned char>((b[8] & 0x3f) | 0x80);
  char text[37];
  std::snprintf(text, sizeof text, "%02x%02x%02x%02x-%02x%02x-%02x%02x-%02x%02x-%02x%02x%02x%02x%02x%02x",
                b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11], b[12], b[13], b[14],
                b[15]);
  return text;
}

std::vector<std::string> random_uuids(int n) {
  std::vector<std::string> ids;
  for (int i = 0; i < n; ++i)
    ids.push_back(random_uuid());
  return ids;
}

// now, UTC, ISO 8601 with milliseconds: an xAPI timestamp
std::string xapi_time_now() {
  return utc_time(std::chrono::system_clock::now(), 3);
}

constexpr const char* kStatuses[] = {"running", "finished", "interrupted", "diverged", "ended_by_instructor"};

// this process as "host:pid:start", the start in clock ticks after boot (a reused pid has another)
std::string start_ticks(long pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  std::getline(in, stat);
  const auto close = stat.rfind(')');  // the command name may hold spaces and parentheses
  if (close == std::string::npos) return {};
  std::istringstream fields(stat.substr(close + 2));
  std::string field;
  for (int n = 3; n <= 22 && fields >> field; ++n)
    if (n == 22) return field;
  return {};
}

std::string this_process() {
  return core::host_name() + ":" + std::to_string(::getpid()) + ":" + start_ticks(::getpid());
}

// a process of this host named by this_process() that has ended (false for other hosts: not known here)
bool ended_here(const std::string& process) {
  const auto first = process.find(':'), second = process.rfind(':');
  if (first == std::string::npos || second == first || process.substr(0, first) != core::host_name())
    return false;
  long pid = 0;
  try {
    pid = std::stol(process.substr(first + 1, second - first - 1));
  } catch (const std::exception&) {
    return false;
  }
  if (pid <= 0) return false;
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) return true;
  return start_ticks(pid) != process.substr(second + 1);
}

}  // namespace

std::string attempt_status(bool diverged, bool interrupted, const sim::Score& score) {
  if (diverged) return "diverged";
  if (interrupted) return "interrupted";
  return score.outcome == sim::Outcome::kEndedByInstructor ? "ended_by_instructor" : "finished";
}

std::string attempt_outcome(const AttemptRow& attempt) {
  if (attempt.status == "finished") return attempt.passed ? "passed" : "failed";
  if (attempt.status == "ended_by_instructor") return "ended by the instructor";
  return attempt.status;
}

std::string utc_time(std::chrono::system_clock::time_point at, int decimals) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(at);
  const long long micros =
      std::chrono::duration_cast<std::chrono::microseconds>(at.time_since_epoch()).count() % 1000000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[40];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  if (decimals == 3)
    std::snprintf(text + n, sizeof text - n, ".%03lldZ", micros / 1000);
  else
    std::snprintf(text + n, sizeof text - n, ".%06lldZ", micros);
  return text;
}

std::string utc_now() {
  return utc_time(std::chrono::system_clock::now(), 6);
}

std::string to_base64(std::string_view bytes) {
  if (sodium_init() < 0) throw std::runtime_error("libsodium could not start");
  std::string out(sodium_base64_encoded_len(bytes.size(), sodium_base64_VARIANT_ORIGINAL), '\0');
  sodium_bin2base64(out.data(), out.size(), reinterpret_cast<const unsigned char*>(bytes.data()),
                    bytes.size(), sodium_base64_VARIANT_ORIGINAL);
  out.resize(out.size() - 1);  // its terminating zero
  return out;
}

std::optional<std::string> from_base64(std::string_view text) {
  if (sodium_init() < 0) throw std::runtime_error("libsodium could not start");
  std::string out(text.size() / 4 * 3 + 3, '\0');
  std::size_t length = 0;
  const char* end = nullptr;
  if (sodium_base642bin(reinterpret_cast<unsigned char*>(out.data()), out.size(), text.data(), text.size(),
                        nullptr, &length, &end, sodium_base64_VARIANT_ORIGINAL) != 0 ||
      end != text.data() + text.size())
    return std::nullopt;
  out.resize(length);
  return out;
}

std::string records_connection(const std::string& connection) {
  if (connection.rfind("postgresql://", 0) == 0) return connection;
  std::string file = connection;
  if (file.rfind("sqlite3://", 0) == 0) {
    file = file.substr(10);
    if (file.rfind("db=", 0) == 0) file = file.substr(3);
    if (file.size() >= 2 && file.front() == '"' && file.back() == '"') file = file.substr(1, file.size() - 2);
  } else if (connection.find("://") != std::string::npos) {
    throw std::runtime_error("records database '" + core::printable(connection) +
                             "': only sqlite3:// and postgresql:// connections are known");
  }
  const auto refuse = [&](const std::string& why) {
    throw std::runtime_error("records database '" + core::printable(connection) + "': " + why);
  };
  if (file.empty()) refuse("no database file named");
  if (file == ":memory:" || file.rfind("file:", 0) == 0)
    refuse("an in-memory or URI database would lose the records: name a file");
  if (const std::string why = core::why_bad_name(file, 4096); !why.empty()) refuse("the file name " + why);
  if (file.find('"') != std::string::npos)
    refuse("a file name with a double quote cannot be passed to SQLite");
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(file, ec)) refuse("is a folder, not a database file");
  const fs::path folder = fs::path(file).has_parent_path() ? fs::path(file).parent_path() : fs::path(".");
  if (!fs::is_directory(folder, ec)) refuse("its folder " + folder.string() + " does not exist");
  return "sqlite3://db=\"" + file + "\"";
}

struct RecordsStore::Impl {
  std::string connection;
  soci::session sql;

  /// Runs `work`; a database error (or a value of the wrong type in a row) becomes one that names the
  /// database and what was being done.
  template <typename Work>
  auto guarded(const std::string& what, Work&& work) -> decltype(work()) {
    try {
      return work();
    } catch (const soci::soci_error& e) {
      throw std::runtime_error("records database '" + connection + "': " + what + ": " + e.what());
    } catch (const std::bad_cast&) {
      throw std::runtime_error("records database '" + connection + "': " + what +
                               ": a value of the wrong type (the database was written by something else?)");
    }
  }

  /// Runs `work` in a transaction that holds the write lock from its start (SQLite: BEGIN IMMEDIATE, so a
  /// read-then-write never meets another writer's lock half-way; PostgreSQL: the attempts table locked
  /// against other writers), committed at the end, rolled back on an error.
  /// What an attempt's xAPI statements say of it (inside the caller's transaction).
  training::xapi::AttemptFacts facts_of(long long attempt) {
    training::xapi::AttemptFacts f;
    f.attempt = attempt;
    sql << "SELECT a.trainee, t.name, a.exercise, a.exercise_version, a.route, a.stage FROM attempts a JOIN "
           "trainees t ON t.id = a.trainee WHERE a.id = :a",
        soci::use(attempt), soci::into(f.trainee), soci::into(f.trainee_name), soci::into(f.exercise),
        soci::into(f.exercise_version), soci::into(f.route), soci::into(f.stage);
    if (!sql.got_data()) throw std::out_of_range("no attempt " + std::to_string(attempt));
    return f;
  }

  /// Queues statements in the xAPI outbox (inside the caller's write transaction).
  void queue(long long attempt, const std::vector<training::xapi::Statement>& statements,
             const std::string& at) {
    for (const training::xapi::Statement& st : statements) {
      long long last = 0;
      soci::indicator ind = soci::i_null;
      sql << "SELECT MAX(id) FROM xapi_outbox", soci::into(last, ind);
      const long long id = (ind == soci::i_ok ? last : 0) + 1;
      sql << "INSERT INTO xapi_outbox (id, statement_id, attempt, verb, statement, queued_at, state, tries,"
             " next_try_at, last_error, sent_at) VALUES (:id, :sid, :a, :verb, :st, :at, 'queued', 0, :next, "
             "'',"
             " '')",
          soci::use(id), soci::use(st.id), soci::use(attempt), soci::use(st.verb), soci::use(st.json),
          soci::use(at), soci::use(at);
    }
  }

  template <typename Work>
  auto write_transaction(Work&& work) -> decltype(work()) {
    const bool sqlite = sql.get_backend_name() == "sqlite3";
    if (sqlite) {
      sql << "BEGIN IMMEDIATE";
    } else {
      sql << "BEGIN";
      sql << "LOCK TABLE attempts IN SHARE ROW EXCLUSIVE MODE";
    }
    try {
      if constexpr (std::is_void_v<decltype(work())>) {
        work();
        sql << "COMMIT";
      } else {
        auto result = work();
        sql << "COMMIT";
        return result;
      }
    } catch (...) {
      try {
        sql << "ROLLBACK";
      } catch (...) {  // the connection is gone: its transaction with it
      }
      throw;
    }
  }

  /// Names of the tables in the database (its current schema on PostgreSQL).
  std::vector<std::string> tables() {
    std::vector<std::string> names;
    const std::string query =
        sql.get_backend_name() == "sqlite3"
            ? "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE 'sqlite_%'"
            : "SELECT table_name FROM information_schema.tables WHERE table_schema = current_schema()";
    soci::rowset<std::string> rows = (sql.prepare << query);
    for (const std::string& name : rows)
      names.push_back(name);
    return names;
  }

  /// The schema's version as the database says (see kSchemaVersion; 0: empty), after checking that every
  /// table is ours with the columns of that version. Throws naming the table otherwise.
  int checked_version() {
    const std::vector<std::string> existing = guarded("checking its tables", [&] { return tables(); });
    for (const std::string& table : existing)
      if (std::none_of(std::begin(kTables), std::end(kTables),
                       [&](const TableColumns& t) { return table == t.table; }))
        throw std::runtime_error("records database '" + connection + "': it holds table '" +
                                 core::printable(table) +
                                 "', which is not harboursim's: a database of something else");
    const auto has = [&](const char* t) {
      return std::find(existing.begin(), existing.end(), t) != existing.end();
    };
    int version = 0;
    if (has("schema_version")) {
      guarded("reading its schema version", [&] {
        soci::indicator ind = soci::i_null;
        sql << "SELECT MAX(version) FROM schema_version", soci::into(version, ind);
        if (ind != soci::i_ok) version = 0;
      });
      if (version > kSchemaVersion)
        throw std::runtime_error("records database '" + connection + "': schema version " +
                                 std::to_string(version) +
                                 " was made by a newer harboursim (this build knows " +
                                 std::to_string(kSchemaVersion) + "): refused, left as it was");
      if (version < 3)
        throw std::runtime_error("records database '" + connection + "': schema version " +
                                 std::to_string(version) + " in a table that came with version 3");
    } else if (has("attempts")) {
      version =
          guarded("checking table 'attempts'", [&] { return has_column("attempts", "process"); }) ? 2 : 1;
    } else if (!existing.empty()) {
      version = 2;  // a version-2 database the console made before any attempt
    }
    for (const TableColumns& t : kTables) {
      const std::string columns = columns_at(t, version);
      if (!has(t.table) || columns.empty()) continue;
      guarded(std::string("table '") + t.table + "' is not the one of schema version " +
                  std::to_string(version) + " (columns " + columns + ")",
              [&] { sql << "SELECT " << columns << " FROM " << t.table << " WHERE 1 = 0"; });
    }
    return version;
  }

  /// Brings the schema to kSchemaVersion, every step and the version's row in one transaction: a database is
  /// at its old version or at the new one, never between (another process upgrading at the same time
  /// waits, then finds it done).
  void upgrade() {
    if (checked_version() == kSchemaVersion) return;
    const bool sqlite = sql.get_backend_name() == "sqlite3";
    guarded("upgrading its schema", [&] {
      sql << (sqlite ? "BEGIN IMMEDIATE" : "BEGIN");
      try {
        if (!sqlite) sql << "SELECT pg_advisory_xact_lock(74707)";  // one upgrader at a time
        const int from = checked_version();
        for (int version = from + 1; version <= kSchemaVersion; ++version) {
          for (const std::string& statement : migration(version)) {
            try {
              sql << statement;
            } catch (const soci::soci_error& e) {
              throw soci::soci_error("from schema version " + std::to_string(version - 1) + " to " +
                                     std::to_string(version) + ": " + e.what() + " (nothing was changed)");
            }
          }
        }
        if (from < kSchemaVersion) sql << "UPDATE schema_version SET version = " << kSchemaVersion;
        sql << "COMMIT";
      } catch (...) {
        try {
          sql << "ROLLBACK";
        } catch (...) {  // the connection is gone: its transaction with it
        }
        throw;
      }
    });
  }

  /// Whether `table` has a column `column` (read from the schema: a busy or lost database is an error, not
  /// a missing column).
  bool has_column(const std::string& table, const std::string& column) {
    int n = 0;
    if (sql.get_backend_name() == "sqlite3")
      sql << "SELECT COUNT(*) FROM pragma_table_info(:t) WHERE name = :c", soci::use(table),
          soci::use(column), soci::into(n);
    else
      sql << "SELECT COUNT(*) FROM information_schema.columns WHERE table_schema = current_schema()"
             " AND table_name = :t AND column_name = :c",
          soci::use(table), soci::use(column), soci::into(n);
    return n > 0;
  }
};

RecordsStore::RecordsStore(const std::string& connection) : impl_(std::make_unique<Impl>()) {
  impl_->connection = connection;
  const std::string soci_connection = records_connection(connection);
  try {
    impl_->sql.open(soci_connection);
  } catch (const std::exception& e) {
    throw std::runtime_error("records database '" + connection + "': " + e.what());
  }
  soci::session& sql = impl_->sql;
  const bool sqlite = sql.get_backend_name() == "sqlite3";
  // settings of this connection only: nothing is written yet
  impl_->guarded("opening", [&] {
    if (sqlite) {
      // another station or the console may be writing: wait for its lock instead of failing at once
      sql << "PRAGMA busy_timeout=10000";
      sql << "PRAGMA synchronous=FULL";
      sql << "PRAGMA foreign_keys=ON";
    } else {
      sql << "SET client_min_messages = WARNING";  // no NOTICE lines for tables that already exist
    }
  });
  if (sqlite)
    impl_->guarded("setting WAL mode", [&] {
      // switching to WAL takes the file's exclusive lock, and SQLite answers "database is locked" at once,
      // without the busy timeout, while another station opening the same file holds it (measured: one of
      // eight stations started together failed so): try again for as long as the busy timeout
      for (int attempt = 1;; ++attempt) {
        try {
          sql << "PRAGMA journal_mode=WAL";
          return;
        } catch (const soci::soci_error& e) {
          if (attempt >= kWalAttempts || std::string(e.what()).find("locked") == std::string::npos) throw;
          std::this_thread::sleep_for(kWalRetry);
        }
      }
    });
  impl_->upgrade();
  mark_interrupted_attempts();
}

int RecordsStore::mark_interrupted_attempts() {
  return impl_->guarded("marking interrupted attempts", [&] {
    std::vector<std::pair<long long, std::string>> running;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare << "SELECT id, process FROM attempts WHERE status = 'running'");
    for (const soci::row& r : rows)
      running.emplace_back(r.get<long long>(0), r.get<std::string>(1));
    int marked = 0;
    for (const auto& [id, process] : running) {
      if (!ended_here(process)) continue;
      const long long a = id;
      const bool marked_here = impl_->write_transaction([&] {
        std::string now_status;
        impl_->sql << "SELECT status FROM attempts WHERE id = :a", soci::use(a), soci::into(now_status);
        if (now_status != "running") return false;  // another process marked it first
        impl_->sql << "UPDATE attempts SET status = 'interrupted' WHERE id = :a", soci::use(a);
        training::xapi::AttemptFacts facts = impl_->facts_of(a);
        facts.status = "interrupted";
        const std::string at = xapi_time_now();
        impl_->queue(a, training::xapi::at_end(facts, at, random_uuids(1)), at);
        return true;
      });
      marked += marked_here ? 1 : 0;
    }
    return marked;
  });
}

RecordsStore::~RecordsStore() = default;

namespace {

void check_trainee(const std::string& id, const std::string& name) {
  if (const std::string why = core::why_bad_name(id, 64); !why.empty())
    throw std::invalid_argument("trainee id '" + core::printable(id, 64) + "' " + why);
  if (const std::string why = core::why_bad_name(name); !why.empty())
    throw std::invalid_argument("trainee name '" + core::printable(name) + "' " + why);
}

}  // namespace

void RecordsStore::ensure_trainee(const std::string& id, const std::string& name) {
  check_trainee(id, name);
  impl_->guarded("adding trainee '" + id + "'", [&] {
    impl_->sql << "INSERT INTO trainees (id, name) VALUES (:id, :name) ON CONFLICT (id) DO NOTHING",
        soci::use(id), soci::use(name);
  });
}

// refuses a name another trainee has (whatever its letters' case): instructors pick trainees by name
void RecordsStore::refuse_name_taken(const std::string& id, const std::string& name) {
  const std::optional<std::string> holder = impl_->guarded("looking up the name '" + name + "'", [&] {
    std::string other;
    soci::indicator found = soci::i_null;
    impl_->sql << "SELECT id FROM trainees WHERE LOWER(name) = LOWER(:name) AND id <> :id", soci::use(name),
        soci::use(id), soci::into(other, found);
    return impl_->sql.got_data() && found == soci::i_ok ? std::optional<std::string>(other) : std::nullopt;
  });
  if (holder)
    throw std::runtime_error("the name '" + name + "' is trainee '" + *holder + "''s: give trainee '" + id +
                             "' a name of its own (a second name, an initial)");
}

void RecordsStore::add_trainee(const std::string& id, const std::string& name) {
  check_trainee(id, name);
  if (has_trainee(id)) throw std::runtime_error("trainee '" + id + "' already exists");
  refuse_name_taken(id, name);
  impl_->guarded("adding trainee '" + id + "'", [&] {
    impl_->sql << "INSERT INTO trainees (id, name) VALUES (:id, :name)", soci::use(id), soci::use(name);
  });
}

void RecordsStore::rename_trainee(const std::string& id, const std::string& name) {
  check_trainee(id, name);
  if (!has_trainee(id)) throw std::out_of_range("no trainee '" + id + "'");
  refuse_name_taken(id, name);
  impl_->guarded("renaming trainee '" + id + "'", [&] {
    impl_->sql << "UPDATE trainees SET name = :name WHERE id = :id", soci::use(name), soci::use(id);
  });
}

bool RecordsStore::has_trainee(const std::string& id) {
  return impl_->guarded("looking up trainee '" + id + "'", [&] {
    int n = 0;
    impl_->sql << "SELECT COUNT(*) FROM trainees WHERE id = :id", soci::use(id), soci::into(n);
    return n > 0;
  });
}

std::vector<TraineeRow> RecordsStore::trainees() {
  return impl_->guarded("reading the trainees", [&] {
    std::vector<TraineeRow> out;
    soci::rowset<soci::row> rows = (impl_->sql.prepare << "SELECT id, name FROM trainees ORDER BY id");
    for (const soci::row& r : rows)
      out.push_back({r.get<std::string>(0), r.get<std::string>(1)});
    return out;
  });
}

std::int64_t RecordsStore::begin_attempt(const std::string& trainee, const std::string& exercise,
                                         std::optional<std::int64_t> parent, std::int64_t branch_step,
                                         const std::string& recording) {
  return begin_attempt(AttemptStart{trainee, exercise, parent, branch_step, recording, "", "", "", {}});
}

std::int64_t RecordsStore::begin_attempt(const AttemptStart& start) {
  const std::string& trainee = start.trainee;
  if (!has_trainee(trainee))
    throw std::runtime_error("no trainee '" + core::printable(trainee) +
                             "' (add it with: harboursim trainees add)");
  const std::string process = this_process();
  return impl_->guarded("starting an attempt of trainee '" + trainee + "'", [&] {
    return impl_->write_transaction([&] {
      long long last = 0;
      soci::indicator ind = soci::i_null;
      impl_->sql << "SELECT MAX(id) FROM attempts", soci::into(last, ind);
      const long long id = (ind == soci::i_ok ? last : 0) + 1;
      long long parent_id = start.parent.value_or(0);
      soci::indicator parent_ind = start.parent ? soci::i_ok : soci::i_null;
      const long long branch = start.branch_step;
      const std::string started_at = xapi_time_now();
      const int autopilot = start.autopilot ? 1 : 0;
      impl_->sql
          << "INSERT INTO attempts (id, trainee, exercise, status, score, passed, parent, branch_step, "
             "recording, process, route, stage, exercise_version, started_at, ended_at, autopilot)"
             " VALUES (:id, :trainee, :exercise, 'running', NULL, 0, :parent, :branch, :recording, :process,"
             " :route, :stage, :version, :started, '', :autopilot)",
          soci::use(id), soci::use(trainee), soci::use(start.exercise), soci::use(parent_id, parent_ind),
          soci::use(branch), soci::use(start.recording), soci::use(process), soci::use(start.route),
          soci::use(start.stage), soci::use(start.exercise_version), soci::use(started_at),
          soci::use(autopilot);
      // the exercise as it ran, once per version
      if (!start.source.text.empty() && start.source.version == start.exercise_version) {
        int kept = 0;
        impl_->sql << "SELECT COUNT(*) FROM exercise_versions WHERE version = :v",
            soci::use(start.source.version), soci::into(kept);
        if (kept == 0)
          impl_->sql
              << "INSERT INTO exercise_versions (version, exercise, folder, text) VALUES (:v, :e, :f, :t)",
              soci::use(start.source.version), soci::use(start.exercise), soci::use(start.source.folder),
              soci::use(start.source.text);
      }
      const std::string at = xapi_time_now();
      impl_->queue(id,
                   training::xapi::at_start(impl_->facts_of(id), at,
                                            random_uuids(training::xapi::statements_at_start())),
                   at);
      return static_cast<std::int64_t>(id);
    });
  });
}

std::optional<io::ExerciseSource> RecordsStore::kept_exercise(const std::string& version) {
  return impl_->guarded(
      "reading exercise version " + core::printable(version), [&]() -> std::optional<io::ExerciseSource> {
        io::ExerciseSource source;
        std::string exercise;
        impl_->sql << "SELECT exercise, folder, text FROM exercise_versions WHERE version = :v",
            soci::use(version), soci::into(exercise), soci::into(source.folder), soci::into(source.text);
        if (!impl_->sql.got_data()) return std::nullopt;
        source.version = io::exercise_text_version(source.text);
        if (source.version != version)
          throw std::runtime_error("the kept text of exercise " + core::printable(exercise) + " version " +
                                   core::printable(version) + " is damaged (its hash is " + source.version +
                                   ")");
        source.file = exercise + " (version " + version + " kept in the records)";
        return source;
      });
}

void RecordsStore::record_move(std::int64_t attempt, int index, double completed_at_s, double cycle_time_s) {
  impl_->guarded("recording move " + std::to_string(index) + " of attempt " + std::to_string(attempt), [&] {
    const long long a = attempt;
    impl_->sql << "INSERT INTO moves (attempt, idx, completed_at_s, cycle_time_s) VALUES (:a, :i, :t, :c)",
        soci::use(a), soci::use(index), soci::use(completed_at_s), soci::use(cycle_time_s);
  });
}

void RecordsStore::record_event(std::int64_t attempt, double at_s, const std::string& kind, double value) {
  impl_->guarded("recording event '" + kind + "' of attempt " + std::to_string(attempt), [&] {
    const long long a = attempt;
    impl_->sql << "INSERT INTO events (attempt, at_s, kind, value) VALUES (:a, :t, :k, :v)", soci::use(a),
        soci::use(at_s), soci::use(kind), soci::use(value);
  });
}

void RecordsStore::finish_attempt(std::int64_t attempt, const sim::Metrics& m, const sim::Score& s,
                                  const std::string& recording, const std::string& status,
                                  std::string_view recording_bytes) {
  if (status != "finished" && status != "interrupted" && status != "diverged" &&
      status != "ended_by_instructor")
    throw std::invalid_argument(
        "an attempt ends finished, interrupted, diverged or ended_by_instructor, not '" + status + "'");
  if (recording_bytes.size() > kMaxStoredRecordingBytes)
    recording_bytes = {};  // too long to keep in the records: its file only
  impl_->guarded("finishing attempt " + std::to_string(attempt), [&] {
    // the final figures and the xAPI statements saying so in one transaction: an attempt is either still
    // running or completely finished
    impl_->write_transaction([&] {
      const long long a = attempt;
      std::vector<std::pair<std::string, double>> values = m.rows();
      values.insert(values.end(), {{"skill_safety", s.skills[0]},
                                   {"skill_precision", s.skills[1]},
                                   {"skill_productivity", s.skills[2]}});
      for (const auto& [name, value] : values) {
        const std::string n = name;
        const double v = value;
        impl_->sql << "INSERT INTO metrics (attempt, name, value) VALUES (:a, :n, :v)", soci::use(a),
            soci::use(n), soci::use(v);
      }
      int idx = 0;
      for (const sim::Score::Deduction& d : s.deductions) {
        const std::string reason = d.reason, skill = sim::skill_name(d.skill);
        const int count = d.count;
        const double points = d.points;
        impl_->sql
            << "INSERT INTO deductions (attempt, idx, reason, skill, count, points) VALUES (:a, :i, :r, "
               ":s, :c, :p)",
            soci::use(a), soci::use(idx), soci::use(reason), soci::use(skill), soci::use(count),
            soci::use(points);
        ++idx;
      }
      if (!recording_bytes.empty()) {
        const long long size = static_cast<long long>(recording_bytes.size());
        const std::string data = to_base64(recording_bytes);
        impl_->sql << "INSERT INTO recordings (attempt, bytes, data) VALUES (:a, :b, :d)", soci::use(a),
            soci::use(size), soci::use(data);
      }
      const double score = s.total;
      const int passed = s.passed ? 1 : 0;
      const std::string ended_at = xapi_time_now();
      impl_->sql << "UPDATE attempts SET status = :st, score = :s, passed = :p, recording = :r, ended_at = :e"
                    " WHERE id = :a",
          soci::use(status), soci::use(score), soci::use(passed), soci::use(recording), soci::use(ended_at),
          soci::use(a);
      training::xapi::AttemptFacts facts = impl_->facts_of(a);
      facts.status = status;
      facts.score = s.total;
      facts.passed = s.passed;
      facts.duration_s = m.time_s;
      facts.metrics = std::move(values);
      const std::string at = xapi_time_now();
      impl_->queue(
          a, training::xapi::at_end(facts, at, random_uuids(training::xapi::statements_at_end(facts))), at);
    });
  });
}

std::optional<std::string> RecordsStore::recording(std::int64_t attempt) {
  std::optional<std::string> out;
  impl_->guarded("reading the recording of attempt " + std::to_string(attempt), [&] {
    const long long a = attempt;
    long long size = 0;
    std::string data;
    soci::indicator found = soci::i_null;
    impl_->sql << "SELECT bytes, data FROM recordings WHERE attempt = :a", soci::into(size, found),
        soci::into(data), soci::use(a);
    if (found != soci::i_ok) return;
    std::optional<std::string> bytes = from_base64(data);
    if (!bytes || static_cast<long long>(bytes->size()) != size)
      throw std::runtime_error("the stored recording of attempt " + std::to_string(attempt) +
                               " is damaged (not the base64 of its " + std::to_string(size) + " bytes)");
    out = std::move(bytes);
  });
  return out;
}

std::optional<AttemptRow> RecordsStore::attempt(std::int64_t id) {
  if (id <= 0) return std::nullopt;
  std::vector<AttemptRow> rows = attempt_rows("", id);
  if (rows.empty()) return std::nullopt;
  return std::move(rows.front());
}

sim::Recording RecordsStore::read_recording_of(const AttemptRow& attempt) {
  std::optional<std::string> kept = recording(attempt.id);
  return kept ? io::parse_recording(attempt.recording, std::move(*kept))
              : io::read_recording(attempt.recording);
}

std::optional<AttemptRow> RecordsStore::attempt_recorded_at(const std::string& path) {
  for (AttemptRow& a : attempts())  // newest first
    if (a.recording == path) return std::move(a);
  return std::nullopt;
}

void RecordsStore::note_team(std::int64_t attempt, const std::string& team, const std::string& role,
                             const std::string& session) {
  const long long id = attempt;
  impl_->guarded("storing attempt " + std::to_string(attempt) + "'s team", [&] {
    impl_->sql << "UPDATE attempts SET team = :t, team_role = :r, team_session = :s WHERE id = :a",
        soci::use(team), soci::use(role), soci::use(session), soci::use(id);
  });
}

std::vector<AttemptRow> RecordsStore::attempts(const std::optional<std::string>& trainee) {
  return attempt_rows(trainee.value_or(""), 0);
}

std::vector<AttemptRow> RecordsStore::session_attempts(const std::string& session) {
  if (session.empty()) return {};
  std::vector<AttemptRow> rows = attempt_rows("", 0, session);
  std::reverse(rows.begin(), rows.end());
  return rows;
}

std::vector<AttemptRow> RecordsStore::attempt_rows(const std::string& who, std::int64_t only_id,
                                                   const std::string& session) {
  std::vector<AttemptRow> out;
  const long long id_wanted = only_id;
  impl_->guarded("reading the attempts", [&] {
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare
             << "SELECT a.id, a.trainee, a.exercise, a.status, a.score, a.passed, a.parent, a.branch_step,"
                " a.recording, a.route, a.stage, a.exercise_version, a.started_at, a.ended_at, a.autopilot,"
                " a.team, a.team_role, a.team_session FROM attempts a WHERE (:who = '' OR "
                "a.trainee = :who2) AND (:id = 0 OR a.id = :id2) AND (:s = '' OR a.team_session = :s2)"
                " ORDER BY a.id DESC",
         soci::use(who), soci::use(who), soci::use(id_wanted), soci::use(id_wanted), soci::use(session),
         soci::use(session));
    for (const soci::row& r : rows) {
      AttemptRow a;
      a.id = r.get<long long>(0);
      impl_->guarded("attempt " + std::to_string(a.id), [&] {
        a.trainee = r.get<std::string>(1);
        a.exercise = r.get<std::string>(2);
        a.status = r.get<std::string>(3);
        if (r.get_indicator(4) == soci::i_ok) a.score = r.get<double>(4);
        a.passed = r.get<int>(5) == 1;
        if (r.get_indicator(6) == soci::i_ok) a.parent = r.get<long long>(6);
        a.branch_step = r.get<long long>(7);
        a.recording = r.get<std::string>(8);
        a.route = r.get<std::string>(9);
        a.stage = r.get<std::string>(10);
        a.exercise_version = r.get<std::string>(11);
        a.started_at = r.get<std::string>(12);
        a.ended_at = r.get<std::string>(13);
        const int autopilot = r.get<int>(14);
        if (autopilot != 0 && autopilot != 1)
          throw soci::soci_error("autopilot is " + std::to_string(autopilot) + ", not 0 or 1");
        a.autopilot = autopilot == 1;
        a.team = r.get<std::string>(15);
        a.team_role = r.get<std::string>(16);
        a.team_session = r.get<std::string>(17);
        const int passed = r.get<int>(5);
        if (std::find(std::begin(kStatuses), std::end(kStatuses), a.status) == std::end(kStatuses))
          throw soci::soci_error("status '" + core::printable(a.status) +
                                 "' is not running, finished, interrupted, diverged or ended_by_instructor");
        if (passed != 0 && passed != 1)
          throw soci::soci_error("passed is " + std::to_string(passed) + ", not 0 or 1");
        if (a.score && !(*a.score >= 0.0 && *a.score <= 100.0))
          throw soci::soci_error("score " + std::to_string(*a.score) + " is outside 0-100");
        if (a.branch_step < 0) throw soci::soci_error("branch step is negative");
      });
      out.push_back(a);
    }
    for (AttemptRow& a : out) {
      const long long id = a.id;
      impl_->sql << "SELECT COUNT(*) FROM moves WHERE attempt = :a", soci::use(id), soci::into(a.moves);
    }
  });
  return out;
}

void RecordsStore::add_account(const AccountRow& account) {
  if (account.role != "administrator" && account.role != "instructor" && account.role != "trainee" &&
      account.role != "signaller")
    throw std::invalid_argument("account role '" + core::printable(account.role) +
                                "': administrator, instructor, signaller or trainee");
  if (const std::string why = core::why_bad_name(account.name, 64); !why.empty())
    throw std::invalid_argument("account name " + why);
  if (account.role == "trainee" && !has_trainee(account.trainee))
    throw std::invalid_argument("account " + account.name + ": no trainee '" +
                                core::printable(account.trainee) + "' in the records");
  impl_->guarded("adding account " + account.name, [&] {
    impl_->write_transaction([&] {
      int n = 0;
      impl_->sql << "SELECT COUNT(*) FROM accounts WHERE name = :n", soci::use(account.name), soci::into(n);
      if (n > 0) throw std::invalid_argument("account " + account.name + " exists");
      std::string trainee = account.trainee;
      soci::indicator present = trainee.empty() ? soci::i_null : soci::i_ok;
      impl_->sql << "INSERT INTO accounts (name, role, password_hash, trainee) VALUES (:n, :r, :h, :t)",
          soci::use(account.name), soci::use(account.role), soci::use(account.password_hash),
          soci::use(trainee, present);
    });
  });
}

namespace {
// a row of SELECT name, role, password_hash, trainee FROM accounts
AccountRow account_row(const soci::row& r) {
  return {r.get<std::string>(0), r.get<std::string>(1), r.get<std::string>(2),
          r.get_indicator(3) == soci::i_null ? std::string() : r.get<std::string>(3)};
}
}  // namespace

std::optional<AccountRow> RecordsStore::account(const std::string& name) {
  return impl_->guarded("reading account", [&]() -> std::optional<AccountRow> {
    soci::rowset<soci::row> rows = (impl_->sql.prepare << "SELECT name, role, password_hash, trainee FROM "
                                                          "accounts WHERE name = :n",
                                    soci::use(name));
    for (const soci::row& r : rows)
      return account_row(r);
    return std::nullopt;
  });
}

std::vector<AccountRow> RecordsStore::accounts() {
  return impl_->guarded("reading accounts", [&] {
    std::vector<AccountRow> accounts;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare << "SELECT name, role, password_hash, trainee FROM accounts ORDER BY name");
    for (const soci::row& r : rows)
      accounts.push_back(account_row(r));
    return accounts;
  });
}

int RecordsStore::account_count() {
  return impl_->guarded("counting accounts", [&] {
    int n = 0;
    impl_->sql << "SELECT COUNT(*) FROM accounts", soci::into(n);
    return n;
  });
}

void RecordsStore::audit(const std::string& account, const std::string& action, const std::string& target,
                         const std::string& detail) {
  audit(AuditRow{utc_now(), account, action, target, detail});
}

void RecordsStore::audit(const AuditRow& row) {
  impl_->guarded("writing the audit log", [&] {
    impl_->sql << "INSERT INTO audit (at, account, action, target, detail) VALUES (:a, :u, :c, :t, :d)",
        soci::use(row.at), soci::use(row.account), soci::use(row.action), soci::use(row.target),
        soci::use(row.detail);
  });
}

std::vector<AuditRow> RecordsStore::audit_log(int newest) {
  return impl_->guarded("reading the audit log", [&] {
    std::vector<AuditRow> log;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare << "SELECT at, account, action, target, detail FROM audit ORDER BY at DESC LIMIT "
                            << std::max(0, newest));
    for (const soci::row& r : rows)
      log.push_back({r.get<std::string>(0), r.get<std::string>(1), r.get<std::string>(2),
                     r.get<std::string>(3), r.get<std::string>(4)});
    return log;
  });
}

std::vector<EventRow> RecordsStore::events(std::int64_t attempt) {
  return impl_->guarded("reading attempt " + std::to_string(attempt) + "'s events", [&] {
    std::vector<EventRow> events;
    const long long id = attempt;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare << "SELECT at_s, kind, value FROM events WHERE attempt = :a ORDER BY at_s",
         soci::use(id));
    for (const soci::row& r : rows)
      events.push_back({r.get<double>(0), r.get<std::string>(1), r.get<double>(2)});
    return events;
  });
}

std::vector<DeductionRow> RecordsStore::deductions(std::int64_t attempt) {
  return impl_->guarded("reading attempt " + std::to_string(attempt) + "'s deductions", [&] {
    std::vector<DeductionRow> deductions;
    const long long id = attempt;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare
             << "SELECT reason, skill, count, points FROM deductions WHERE attempt = :a ORDER BY idx",
         soci::use(id));
    for (const soci::row& r : rows)
      deductions.push_back({r.get<std::string>(0), r.get<std::string>(1), r.get<int>(2), r.get<double>(3)});
    return deductions;
  });
}

std::vector<std::pair<std::string, double>> RecordsStore::metrics(std::int64_t attempt) {
  return impl_->guarded("reading attempt " + std::to_string(attempt) + "'s metrics", [&] {
    std::vector<std::pair<std::string, double>> metrics;
    const long long id = attempt;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare << "SELECT name, value FROM metrics WHERE attempt = :a ORDER BY name",
         soci::use(id));
    for (const soci::row& r : rows)
      metrics.emplace_back(r.get<std::string>(0), r.get<double>(1));
    return metrics;
  });
}

std::vector<training::AttemptFigures> RecordsStore::attempt_figures(
    const std::optional<std::string>& trainee) {
  std::vector<AttemptRow> rows = attempts(trainee);  // checked as attempts() checks them
  std::reverse(rows.begin(), rows.end());
  std::map<std::int64_t, std::map<std::string, double>> metrics_of;
  impl_->guarded("reading the attempts' metrics", [&] {
    const std::string who = trainee.value_or("");
    soci::rowset<soci::row> metric_rows =
        (impl_->sql.prepare << "SELECT m.attempt, m.name, m.value FROM metrics m JOIN attempts a ON a.id = "
                               "m.attempt WHERE :who = '' OR a.trainee = :who2",
         soci::use(who), soci::use(who));
    for (const soci::row& r : metric_rows)
      metrics_of[r.get<long long>(0)][r.get<std::string>(1)] = r.get<double>(2);
  });
  std::vector<training::AttemptFigures> out;
  out.reserve(rows.size());
  for (const AttemptRow& a : rows)
    out.push_back({a.id, a.trainee, a.exercise, a.exercise_version, a.route, a.stage, a.status, a.score,
                   a.passed, std::move(metrics_of[a.id])});
  return out;
}

namespace {

XapiRow xapi_row(const soci::row& r) {
  XapiRow x;
  x.id = r.get<long long>(0);
  x.statement_id = r.get<std::string>(1);
  x.attempt = r.get<long long>(2);
  x.verb = r.get<std::string>(3);
  x.statement = r.get<std::string>(4);
  x.queued_at = r.get<std::string>(5);
  x.state = r.get<std::string>(6);
  x.tries = r.get<int>(7);
  x.next_try_at = r.get<std::string>(8);
  x.last_error = r.get<std::string>(9);
  x.sent_at = r.get<std::string>(10);
  return x;
}

constexpr const char* kXapiColumns =
    "SELECT id, statement_id, attempt, verb, statement, queued_at, state, tries, next_try_at, last_error, "
    "sent_at"
    " FROM xapi_outbox ";

}  // namespace

std::vector<XapiRow> RecordsStore::xapi_due(const std::string& now, int most) {
  return impl_->guarded("reading the xAPI outbox", [&] {
    std::vector<XapiRow> due;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare << std::string(kXapiColumns) +
                                   "WHERE state = 'queued' AND next_try_at <= :now ORDER BY id LIMIT :most",
         soci::use(now), soci::use(most));
    for (const soci::row& r : rows)
      due.push_back(xapi_row(r));
    return due;
  });
}

std::vector<XapiRow> RecordsStore::xapi_outbox() {
  return impl_->guarded("reading the xAPI outbox", [&] {
    std::vector<XapiRow> all;
    soci::rowset<soci::row> rows = (impl_->sql.prepare << std::string(kXapiColumns) + "ORDER BY id");
    for (const soci::row& r : rows)
      all.push_back(xapi_row(r));
    return all;
  });
}

std::map<std::string, int> RecordsStore::xapi_counts() {
  return impl_->guarded("counting the xAPI outbox", [&] {
    std::map<std::string, int> counts;
    for (const std::string state : {"queued", "sent", "rejected"}) {
      int n = 0;
      impl_->sql << "SELECT COUNT(*) FROM xapi_outbox WHERE state = :s", soci::use(state), soci::into(n);
      counts[state] = n;
    }
    return counts;
  });
}

void RecordsStore::xapi_sent(std::int64_t id, const std::string& at) {
  impl_->guarded("marking xAPI statement " + std::to_string(id) + " sent", [&] {
    const long long row = id;
    impl_->sql << "UPDATE xapi_outbox SET state = 'sent', tries = tries + 1, sent_at = :at, last_error = ''"
                  " WHERE id = :id",
        soci::use(at), soci::use(row);
  });
}

void RecordsStore::xapi_failed(std::int64_t id, const std::string& error, const std::string& next_try_at,
                               bool rejected) {
  impl_->guarded("marking xAPI statement " + std::to_string(id) + " failed", [&] {
    const long long row = id;
    const std::string state = rejected ? "rejected" : "queued";
    const std::string why = error.substr(0, 2000);
    impl_->sql
        << "UPDATE xapi_outbox SET state = :state, tries = tries + 1, next_try_at = :next, last_error = :e"
           " WHERE id = :id",
        soci::use(state), soci::use(next_try_at), soci::use(why), soci::use(row);
  });
}

int RecordsStore::schema_version() {
  return impl_->guarded("reading its schema version", [&] {
    int version = 0;
    impl_->sql << "SELECT MAX(version) FROM schema_version", soci::into(version);
    return version;
  });
}

bool RecordsStore::enrol(const std::string& trainee, const std::string& route, const std::string& account) {
  if (!has_trainee(trainee)) throw std::out_of_range("no trainee '" + core::printable(trainee) + "'");
  if (const std::string why = core::why_bad_name(route, 64); !why.empty())
    throw std::invalid_argument("route '" + core::printable(route, 64) + "' " + why);
  const std::string when = utc_now();
  return impl_->guarded("enrolling trainee '" + trainee + "' in route '" + route + "'", [&] {
    return impl_->write_transaction([&] {
      int n = 0;
      impl_->sql << "SELECT COUNT(*) FROM enrolments WHERE trainee = :t AND route = :r", soci::use(trainee),
          soci::use(route), soci::into(n);
      if (n > 0) return false;
      impl_->sql << "INSERT INTO enrolments (trainee, route, at, account) VALUES (:t, :r, :a, :u)",
          soci::use(trainee), soci::use(route), soci::use(when), soci::use(account);
      return true;
    });
  });
}

std::vector<EnrolmentRow> RecordsStore::enrolments(const std::optional<std::string>& trainee) {
  const std::string who = trainee.value_or("");
  return impl_->guarded("reading the enrolments", [&] {
    std::vector<EnrolmentRow> out;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare
             << "SELECT trainee, route, at, account FROM enrolments WHERE :w = '' OR trainee = "
                ":w2 ORDER BY at, trainee, route",
         soci::use(who), soci::use(who));
    for (const soci::row& r : rows)
      out.push_back(
          {r.get<std::string>(0), r.get<std::string>(1), r.get<std::string>(2), r.get<std::string>(3)});
    return out;
  });
}

void RecordsStore::add_override(const std::string& trainee, const std::string& route,
                                const training::Override& decision) {
  if (decision.action != "sign_off" && decision.action != "retry")
    throw std::invalid_argument("a decision on a stage is sign_off or retry, not '" +
                                core::printable(decision.action) + "'");
  if (const std::string why = core::why_bad_name(decision.reason, 500); !why.empty())
    throw std::invalid_argument("the reason " + why);
  if (const std::string why = core::why_bad_name(decision.stage, 64); !why.empty())
    throw std::invalid_argument("the stage " + why);
  const auto enrolled = enrolments(trainee);
  if (std::none_of(enrolled.begin(), enrolled.end(), [&](const EnrolmentRow& e) { return e.route == route; }))
    throw std::out_of_range("trainee '" + core::printable(trainee) + "' is not enrolled in route '" +
                            core::printable(route) + "'");
  const std::string when = utc_now();
  impl_->guarded("storing a decision on '" + trainee + "' " + route + "/" + decision.stage, [&] {
    impl_->sql << "INSERT INTO route_overrides (trainee, route, stage, action, reason, account, at)"
                  " VALUES (:t, :r, :s, :a, :why, :u, :at)",
        soci::use(trainee), soci::use(route), soci::use(decision.stage), soci::use(decision.action),
        soci::use(decision.reason), soci::use(decision.account), soci::use(when);
  });
}

std::vector<training::Override> RecordsStore::overrides(const std::string& trainee,
                                                        const std::string& route) {
  return impl_->guarded("reading the decisions on '" + trainee + "' " + route, [&] {
    std::vector<training::Override> out;
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare << "SELECT stage, action, reason, account, at FROM route_overrides"
                               " WHERE trainee = :t AND route = :r ORDER BY at",
         soci::use(trainee), soci::use(route));
    for (const soci::row& r : rows)
      out.push_back({r.get<std::string>(0), r.get<std::string>(1), r.get<std::string>(2),
                     r.get<std::string>(3), r.get<std::string>(4)});
    return out;
  });
}

std::vector<training::StageAttempt> RecordsStore::stage_attempts(const std::string& trainee,
                                                                 const std::string& route) {
  std::vector<training::StageAttempt> out;
  std::vector<long long> ids;
  impl_->guarded("reading '" + trainee + "''s attempts on route " + route, [&] {
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare << "SELECT id, stage, status, score, passed FROM attempts"
                               " WHERE trainee = :t AND route = :r ORDER BY id",
         soci::use(trainee), soci::use(route));
    for (const soci::row& r : rows) {
      training::StageAttempt a;
      ids.push_back(r.get<long long>(0));
      a.stage = r.get<std::string>(1);
      a.status = r.get<std::string>(2);
      if (r.get_indicator(3) == soci::i_ok) a.score = r.get<double>(3);
      a.passed = r.get<int>(4) == 1;
      out.push_back(a);
    }
  });
  for (std::size_t n = 0; n < out.size(); ++n)
    for (const auto& [name, value] : metrics(ids[n]))
      out[n].metrics[name] = value;
  return out;
}

void record_progress(RecordsStore& db, std::int64_t attempt, const sim::Progress& before,
                     const sim::Progress& now) {
  for (int n = before.moves_completed; n < now.moves_completed; ++n) {
    // the newest moves' cycle times (a look after every step sees at most one new move)
    const int back = now.moves_completed - 1 - n;
    const double cycle_s = back < static_cast<int>(sim::Progress::kRecentMoves)
                               ? now.recent_cycle_times_s[sim::Progress::kRecentMoves - 1 - back]
                               : 0.0;
    db.record_move(attempt, n + 1, now.time_s, cycle_s);
  }
  for (const sim::CountedEvent& e : sim::counted_events(before, now))
    db.record_event(attempt, now.time_s, e.kind, e.value);
}

}  // namespace harbour::records
