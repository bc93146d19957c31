#include "harbour/io/RecordsStore.h"

#include <soci/soci.h>

#include <stdexcept>
#include <string>
#include <typeinfo>
#include <utility>

namespace harbour::io {
namespace {

// every table with the columns this build reads and writes
constexpr std::pair<const char*, const char*> kTables[] = {
    {"trainees", "id, name"},
    {"attempts", "id, trainee, exercise, status, score, passed, parent, branch_step, recording"},
    {"moves", "attempt, idx, completed_at_s, cycle_time_s"},
    {"events", "attempt, at_s, kind, value"},
    {"metrics", "attempt, name, value"},
};

}  // namespace

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
};

RecordsStore::RecordsStore(const std::string& connection) : impl_(std::make_unique<Impl>()) {
  impl_->connection = connection;
  try {
    impl_->sql.open(connection);
    soci::session& sql = impl_->sql;
    if (sql.get_backend_name() == "sqlite3") {
      // another station or the console may be writing: wait for its lock instead of failing at once
      sql << "PRAGMA busy_timeout=10000";
      sql << "PRAGMA journal_mode=WAL";
      sql << "PRAGMA synchronous=FULL";
      sql << "PRAGMA foreign_keys=ON";
    } else if (sql.get_backend_name() == "postgresql") {
      sql << "SET client_min_messages = WARNING";  // no NOTICE lines for tables that already exist
    }
    // the portable subset of SQL that SQLite and PostgreSQL both accept
    sql << "CREATE TABLE IF NOT EXISTS trainees (id TEXT PRIMARY KEY, name TEXT NOT NULL)";
    sql << "CREATE TABLE IF NOT EXISTS attempts (id BIGINT PRIMARY KEY, trainee TEXT NOT NULL REFERENCES "
           "trainees(id),"
           " exercise TEXT NOT NULL, status TEXT NOT NULL, score DOUBLE PRECISION, passed INTEGER NOT NULL,"
           " parent BIGINT, branch_step BIGINT NOT NULL, recording TEXT NOT NULL)";
    sql << "CREATE TABLE IF NOT EXISTS moves (attempt BIGINT NOT NULL REFERENCES attempts(id), idx INTEGER "
           "NOT NULL,"
           " completed_at_s DOUBLE PRECISION NOT NULL, cycle_time_s DOUBLE PRECISION NOT NULL, PRIMARY KEY "
           "(attempt, idx))";
    sql << "CREATE TABLE IF NOT EXISTS events (attempt BIGINT NOT NULL REFERENCES attempts(id),"
           " at_s DOUBLE PRECISION NOT NULL, kind TEXT NOT NULL, value DOUBLE PRECISION NOT NULL)";
    sql << "CREATE TABLE IF NOT EXISTS metrics (attempt BIGINT NOT NULL REFERENCES attempts(id), name TEXT "
           "NOT NULL,"
           " value DOUBLE PRECISION NOT NULL, PRIMARY KEY (attempt, name))";
  } catch (const std::exception& e) {
    throw std::runtime_error("records database '" + connection + "': " + e.what());
  }
  // tables of the same name made by something else: refuse before anything is written into them
  for (const auto& [table, columns] : kTables)
    impl_->guarded(
        std::string("table '") + table + "' is not the one this build uses (columns " + columns + ")",
        [&] { impl_->sql << "SELECT " << columns << " FROM " << table << " WHERE 1 = 0"; });
}

RecordsStore::~RecordsStore() = default;

void RecordsStore::add_trainee(const std::string& id, const std::string& name) {
  if (id.empty() || name.empty()) throw std::runtime_error("a trainee needs an id and a name");
  if (has_trainee(id)) throw std::runtime_error("trainee '" + id + "' already exists");
  impl_->guarded("adding trainee '" + id + "'", [&] {
    impl_->sql << "INSERT INTO trainees (id, name) VALUES (:id, :name)", soci::use(id), soci::use(name);
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
                                         std::optional<std::int64_t> parent, std::int64_t branch_step) {
  if (!has_trainee(trainee))
    throw std::runtime_error("no trainee '" + trainee + "' (add it with: harboursim trainees add)");
  return impl_->guarded("starting an attempt of trainee '" + trainee + "'", [&] {
    soci::transaction tr(impl_->sql);
    long long last = 0;
    soci::indicator ind = soci::i_null;
    impl_->sql << "SELECT MAX(id) FROM attempts", soci::into(last, ind);
    const long long id = (ind == soci::i_ok ? last : 0) + 1;
    long long parent_id = parent.value_or(0);
    soci::indicator parent_ind = parent ? soci::i_ok : soci::i_null;
    const long long branch = branch_step;
    impl_->sql << "INSERT INTO attempts (id, trainee, exercise, status, score, passed, parent, branch_step, "
                  "recording)"
                  " VALUES (:id, :trainee, :exercise, 'running', NULL, 0, :parent, :branch, '')",
        soci::use(id), soci::use(trainee), soci::use(exercise), soci::use(parent_id, parent_ind),
        soci::use(branch);
    tr.commit();
    return static_cast<std::int64_t>(id);
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
                                  const std::string& recording) {
  impl_->guarded("finishing attempt " + std::to_string(attempt), [&] {
    // the final figures in one transaction: an attempt is either still running or completely finished
    soci::transaction tr(impl_->sql);
    const long long a = attempt;
    const std::pair<const char*, double> values[] = {{"time_s", m.time_s},
                                                     {"moves_completed", m.moves_completed},
                                                     {"moves_per_hour", m.moves_per_hour},
                                                     {"collisions", m.collisions},
                                                     {"worst_collision_mps", m.worst_collision_mps},
                                                     {"collision_impulse_ns", m.collision_impulse_ns},
                                                     {"container_collisions", m.container_collisions},
                                                     {"cell_guide_collisions", m.cell_guide_collisions},
                                                     {"ship_collisions", m.ship_collisions},
                                                     {"hard_landings", m.hard_landings},
                                                     {"worst_landing_mps", m.worst_landing_mps},
                                                     {"sway_landings", m.sway_landings},
                                                     {"twistlock_misuse", m.twistlock_misuse},
                                                     {"overloads", m.overloads},
                                                     {"limit_hits", m.limit_hits},
                                                     {"emergency_stops", m.emergency_stops},
                                                     {"unwarned_gantry_travel", m.unwarned_gantry_travel},
                                                     {"skill_safety", s.skills[0]},
                                                     {"skill_precision", s.skills[1]},
                                                     {"skill_productivity", s.skills[2]},
                                                     {"hoist_energy_j", m.hoist_energy_j},
                                                     {"travel_energy_j", m.travel_energy_j}};
    for (const auto& [name, value] : values) {
      const std::string n = name;
      const double v = value;
      impl_->sql << "INSERT INTO metrics (attempt, name, value) VALUES (:a, :n, :v)", soci::use(a),
          soci::use(n), soci::use(v);
    }
    const double score = s.total;
    const int passed = s.passed ? 1 : 0;
    impl_->sql
        << "UPDATE attempts SET status = 'finished', score = :s, passed = :p, recording = :r WHERE id = :a",
        soci::use(score), soci::use(passed), soci::use(recording), soci::use(a);
    tr.commit();
  });
}

std::vector<AttemptRow> RecordsStore::attempts(const std::optional<std::string>& trainee) {
  std::vector<AttemptRow> out;
  const std::string who = trainee.value_or("");
  impl_->guarded("reading the attempts", [&] {
    soci::rowset<soci::row> rows =
        (impl_->sql.prepare
             << "SELECT a.id, a.trainee, a.exercise, a.status, a.score, a.passed, a.parent, a.branch_step,"
                " a.recording FROM attempts a WHERE :who = '' OR a.trainee = :who2 ORDER BY a.id DESC",
         soci::use(who), soci::use(who));
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
        const int passed = r.get<int>(5);
        if (a.status != "running" && a.status != "finished")
          throw soci::soci_error("status '" + a.status + "' is neither running nor finished");
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

}  // namespace harbour::io
