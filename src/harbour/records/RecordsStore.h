#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "harbour/io/ExerciseFiles.h"
#include "harbour/sim/Evaluation.h"
#include "harbour/sim/Recording.h"
#include "harbour/training/Cohort.h"
#include "harbour/training/Route.h"

namespace harbour::records {

/// A trainee in the records.
struct TraineeRow {
  std::string id;
  std::string name;
};

/// An exercise attempt in the records.
struct AttemptRow {
  std::int64_t id = 0;
  std::string trainee;
  std::string exercise;
  /// running, finished, interrupted (its process ended first), diverged (physics), ended_by_instructor
  std::string status;
  std::optional<double> score;
  bool passed = false;
  std::optional<std::int64_t> parent;  ///< the attempt an instructor took over from
  std::int64_t branch_step = 0;
  std::string recording;     ///< recording file (given at the start: an interrupted one's replayable prefix)
  int moves = 0;             ///< moves stored so far
  std::string route, stage;  ///< the training route stage it was run for ("" : none)
  std::string exercise_version;      ///< the exercise file's content hash (io::exercise_version; "" : before)
  std::string started_at, ended_at;  ///< UTC, ISO 8601 ("" : before schema version 7; ended: still running)
  bool autopilot = false;            ///< the scripted operator drove it, not a trainee
  /// A team session's member: its team, its role, and the session ("TEAM@START": every member that heard the
  /// others stores the same); "" : alone, or before schema version 8.
  std::string team, team_role, team_session;
};

/// How an attempt is stored as ended: diverged (the physics stopped it), interrupted (its process ended
/// first), ended_by_instructor (sim::Outcome::kEndedByInstructor: neither passed nor failed), else finished.
std::string attempt_status(bool diverged, bool interrupted, const sim::Score& score);
/// An attempt's result in words: passed, failed, ended by the instructor, interrupted, diverged, running.
std::string attempt_outcome(const AttemptRow& attempt);

/// What an attempt starts with.
struct AttemptStart {
  std::string trainee, exercise;
  std::optional<std::int64_t> parent;  ///< the attempt an instructor took over from
  std::int64_t branch_step = 0;
  std::string recording;
  std::string route, stage, exercise_version;
  io::ExerciseSource source;  ///< the exercise as it runs, kept by its version (none: its text is not kept)
  bool autopilot = false;     ///< the scripted operator drives it
};

/// A trainee enrolled in a route: when and by whom (UTC, ISO 8601).
struct EnrolmentRow {
  std::string trainee, route, at, account;
};

/// A console account: an administrator, an instructor, or a trainee (who sees only their own results).
struct AccountRow {
  std::string name;
  std::string role;           ///< administrator, instructor, signaller, trainee
  std::string password_hash;  ///< the Argon2id hash string (libsodium's crypto_pwhash_str)
  std::string trainee;        ///< a trainee account's trainee id ("" for the others)
};

/// One instructor action in the audit log: who, when (UTC, ISO 8601 with microseconds), what, on what.
struct AuditRow {
  std::string at, account, action, target, detail;
};

/// `at`, UTC, ISO 8601 with `decimals` (3 or 6) digits of the second: such times compare as text.
std::string utc_time(std::chrono::system_clock::time_point at, int decimals);
/// Now, UTC, ISO 8601 with microseconds: how the records stamp what they store.
std::string utc_now();
/// Bytes as base64 (the original alphabet, padded), and back: nullopt where `text` is not base64 throughout.
std::string to_base64(std::string_view bytes);
std::optional<std::string> from_base64(std::string_view text);

/// An event of an attempt as stored (a collision, a hard landing, an instructor's command, ...).
struct EventRow {
  double at_s = 0.0;
  std::string kind;
  double value = 0.0;
};

/// What a finished attempt's score took off: why, against which skill, how often, how many points in all.
struct DeductionRow {
  std::string reason, skill;
  int count = 0;
  double points = 0.0;
};

/// An xAPI statement in the outbox: queued (to be sent when next_try_at has come), sent, or rejected (the
/// LRS refused it: sending it again would not help).
struct XapiRow {
  std::int64_t id = 0, attempt = 0;
  std::string statement_id, verb, statement, queued_at, state, next_try_at, last_error, sent_at;
  int tries = 0;
};

/// The SOCI connection string for `connection`: "sqlite3://db=FILE", "sqlite3://FILE" or a plain FILE (an
/// SQLite file that must persist: not ":memory:", not empty, its folder must exist), or
/// "postgresql://..." as it is. Throws std::invalid_argument saying what is wrong.
std::string records_connection(const std::string& connection);

/// Largest recording kept in the records database with its attempt [bytes] (a longer one is replayed from its
/// file only).
inline constexpr std::size_t kMaxStoredRecordingBytes = std::size_t{64} << 20;

/// The trainee database: trainees, attempts, moves and events as they happen, final metrics and score. One
/// interface over SOCI: "sqlite3://db=<file>" (the default: one file, WAL, waiting up to 10 s for another
/// writer's lock) or "postgresql://dbname=... host=..." for a training centre; the SQL is the portable subset
/// both accept. Every write commits at once, so a crash loses nothing already measured; any number of
/// stations may write at once. An attempt remembers the process running it: when a database is opened,
/// attempts still "running" whose process on this host is gone are marked interrupted.
class RecordsStore {
 public:
  /// Opens (and creates the schema in) a database; throws std::runtime_error naming the connection on
  /// failure, when the database holds tables that are not ours, or when a table of ours lacks the columns
  /// this build uses: checked before anything is written, so a refused database is left as it was.
  /// Every later error names the connection and what was being done; attempts() refuses a row whose status,
  /// pass flag, score or branch step no run of ours could have written, naming the attempt.
  explicit RecordsStore(const std::string& connection);
  ~RecordsStore();
  RecordsStore(const RecordsStore&) = delete;
  RecordsStore& operator=(const RecordsStore&) = delete;

  /// Adds a trainee; the id and name are names (core::why_bad_name), the id at most 64 bytes, the name no
  /// other trainee's (whatever the case of its ASCII letters: std::runtime_error).
  void add_trainee(const std::string& id, const std::string& name);
  /// Adds the trainee unless one with this id exists (two stations may do so at once).
  void ensure_trainee(const std::string& id, const std::string& name);
  /// Changes a trainee's name (the id stays: attempts refer to it). Throws std::invalid_argument for a bad
  /// name, std::out_of_range for an unknown trainee, std::runtime_error for a name another trainee has.
  void rename_trainee(const std::string& id, const std::string& name);
  std::vector<TraineeRow> trainees();
  bool has_trainee(const std::string& id);

  /// Starts an attempt, owned by this process, and returns its id.
  std::int64_t begin_attempt(const std::string& trainee, const std::string& exercise,
                             std::optional<std::int64_t> parent = std::nullopt, std::int64_t branch_step = 0,
                             const std::string& recording = "");
  std::int64_t begin_attempt(const AttemptStart& start);
  void record_move(std::int64_t attempt, int index, double completed_at_s, double cycle_time_s);
  void record_event(std::int64_t attempt, double at_s, const std::string& kind, double value);
  /// Stores the final metrics and score; `status` is finished, interrupted (stopped before its end, e.g.
  /// Ctrl-C) or diverged (the physics stopped it).
  /// `recording_bytes`: the recording file's content, kept with the attempt in the same transaction (so that
  /// a console or station on another PC replays it and continues it; not kept past kMaxStoredRecordingBytes).
  /// The attempt was a team session's member (AttemptRow::team, team_role, team_session).
  void note_team(std::int64_t attempt, const std::string& team, const std::string& role,
                 const std::string& session);
  void finish_attempt(std::int64_t attempt, const sim::Metrics& metrics, const sim::Score& score,
                      const std::string& recording, const std::string& status = "finished",
                      std::string_view recording_bytes = {});
  /// The recording kept with an attempt (nullopt: none kept, e.g. it was interrupted); throws naming the
  /// attempt when the copy is damaged.
  std::optional<std::string> recording(std::int64_t attempt);
  /// An attempt's recording read: the copy kept here, else its file where its station wrote it (throws
  /// io::RecordingFileError naming the file, or naming the attempt for a damaged copy).
  sim::Recording read_recording_of(const AttemptRow& attempt);
  /// Marks attempts still running whose process on this host has ended as interrupted; returns how many.
  /// (The constructor does this.)
  int mark_interrupted_attempts();
  /// Attempts, newest first, optionally of one trainee.
  std::vector<AttemptRow> attempts(const std::optional<std::string>& trainee = std::nullopt);
  /// The exercise text an attempt of version `version` ran (none: not kept, an attempt before the records
  /// kept them); throws naming it when the kept text does not hash to its version.
  std::optional<io::ExerciseSource> kept_exercise(const std::string& version);
  /// The attempt whose recording is the file `path`: the newest of them when a path was used again (the file
  /// holds the last run written to it); none when no attempt was recorded there (a take-over's check).
  std::optional<AttemptRow> attempt_recorded_at(const std::string& path);
  /// One attempt (none: no such attempt).
  std::optional<AttemptRow> attempt(std::int64_t id);
  /// The attempts of team session `session` (its members'; AttemptRow::team_session), oldest first.
  std::vector<AttemptRow> session_attempts(const std::string& session);
  /// An attempt's events in time order, its final metrics by name, and what its score took off (none for an
  /// attempt not finished, or finished before the records kept them).
  std::vector<EventRow> events(std::int64_t attempt);
  std::vector<DeductionRow> deductions(std::int64_t attempt);
  std::vector<std::pair<std::string, double>> metrics(std::int64_t attempt);
  /// Attempts, oldest first, optionally of one trainee, each with its stored metrics (one read of each
  /// table): what the cohort views and the reports are made of.
  std::vector<training::AttemptFigures> attempt_figures(
      const std::optional<std::string>& trainee = std::nullopt);

  /// Adds a console account; throws std::invalid_argument for a bad name or role, a trainee account whose
  /// trainee is not in the records, or a name taken.
  void add_account(const AccountRow& account);
  std::optional<AccountRow> account(const std::string& name);
  int account_count();
  /// Every account by name (the password hashes included: for the console's own use).
  std::vector<AccountRow> accounts();
  /// Appends an entry stamped earlier (its `at`) to the audit log.
  void audit(const AuditRow& row);
  /// Appends to the audit log (every instructor action, who and when).
  void audit(const std::string& account, const std::string& action, const std::string& target,
             const std::string& detail);
  /// The newest `newest` entries, newest first.
  std::vector<AuditRow> audit_log(int newest);

  /// Queued xAPI statements whose next try has come (`now`: UTC ISO 8601, as they are stored), oldest first,
  /// at most `most`. Each attempt's statements are queued in the transaction that begins or ends it.
  std::vector<XapiRow> xapi_due(const std::string& now, int most);
  /// Every statement of the outbox, oldest first (for a status and the tests).
  std::vector<XapiRow> xapi_outbox();
  /// How many statements are queued, sent and rejected.
  std::map<std::string, int> xapi_counts();
  void xapi_sent(std::int64_t id, const std::string& at);
  /// A try that failed: queued again for `next_try_at`, or rejected for good; the error is kept.
  void xapi_failed(std::int64_t id, const std::string& error, const std::string& next_try_at, bool rejected);

  /// The schema version of the database (the build's latest once opened: opening upgrades it).
  int schema_version();

  /// Enrols a trainee in a route (by its id, the route file's stem); enrolling again changes nothing and
  /// returns false. Throws std::out_of_range for an unknown trainee.
  bool enrol(const std::string& trainee, const std::string& route, const std::string& account);
  /// Enrolments, of one trainee or of all, in the order they were made.
  std::vector<EnrolmentRow> enrolments(const std::optional<std::string>& trainee = std::nullopt);
  /// Stores an instructor's decision on a trainee's route stage (sign_off or retry) with its reason;
  /// throws std::invalid_argument for another action or an empty reason, std::out_of_range when the trainee
  /// is not enrolled in the route.
  void add_override(const std::string& trainee, const std::string& route, const training::Override& decision);
  std::vector<training::Override> overrides(const std::string& trainee, const std::string& route);
  /// The trainee's attempts at the route's stages with their stored metrics, oldest first.
  std::vector<training::StageAttempt> stage_attempts(const std::string& trainee, const std::string& route);

 private:
  void refuse_name_taken(const std::string& id, const std::string& name);
  // the attempts of `who` ("": everyone's), or only attempt `only_id` (0: all), newest first
  std::vector<AttemptRow> attempt_rows(const std::string& who, std::int64_t only_id,
                                       const std::string& session = "");
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Stores what the evaluator counted since `before` (moves done, collisions, hard landings, ...) as moves
/// and events of `attempt`, stamped with the moment they happened.
void record_progress(RecordsStore& db, std::int64_t attempt, const sim::Progress& before,
                     const sim::Progress& now);

}  // namespace harbour::records
