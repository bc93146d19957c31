#pragma once

// What the instructor console's parts share (not for use outside console/): the server's types, the console
// with its route table and resources, and the API's JSON forms. The server (`Console.cpp`: HTTP, WebSocket,
// TLS, the route table, polling) and one file per resource (`Accounts.cpp`, `Stations.cpp`,
// `TraineeRecords.cpp`, `DesignerApi.cpp`, `Replays.cpp`) define the console's members; `ApiJson.cpp` the
// forms.
#include <utility>  // before Boost.Asio 1.74, which uses std::exchange without it

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "harbour/console/Console.h"
#include "harbour/console/Designer.h"
#include "harbour/ig/Visuals.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/net/DdsLink.h"
#include "harbour/records/AuditWriter.h"
#include "harbour/records/CentreRoutes.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/records/XapiSender.h"
#include "harbour/scene/BulkView.h"
#include "harbour/sim/Recording.h"
#include "harbour/sim/SessionPlayer.h"
#include "harbour/training/Route.h"

namespace harbour::console {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr int kMaxJsonDepth = 8;
constexpr auto kSessionLifetime = std::chrono::hours(12);
constexpr auto kAckTimeout = std::chrono::seconds(3);
constexpr int kLoginFailuresAllowed = 5;  // per minute, per address and per account
constexpr auto kLoginWindow = std::chrono::seconds(60);

// a stored figure's words, for a page to label it and show it in its unit (shown = stored × scale)
json figure_words_json(const std::string& name);

// an attempt's event: when, what (the stored kind and value) and in words
json attempt_event_json(double at_s, const std::string& kind, double value);

// how deep `text` nests arrays and objects (outside strings): refused before parsing when too deep
int json_depth(const std::string& text);

// a query parameter's value, percent-decoded ('+' a space); "" when absent or not decodable
std::string query_param(const std::string& query, const std::string& key);

// a JSON object from a request or message body, or why not: too deep, not JSON, not an object, or an object
// that gives a key twice (parsers disagree on which one counts: the last here, the first elsewhere)
std::optional<json> parse_object(const std::string& text, std::string& why);

// a string field of at most `longest` bytes with no control or bidirectional formatting characters (a
// password: no control characters); "" and a reason when missing or bad
std::optional<std::string> text_field(const json& body, const char* field, std::size_t longest,
                                      std::string& why, bool required = true, bool password = false);

// JSON text; strings that are not UTF-8 (a foreign DDS peer's, a database's) are repaired, not thrown on
std::string dump(const json& value);

std::string content_type(const std::filesystem::path& file);

// The shipped team sessions (data/teams) and their roles; a team file in error is listed with its error.
json team_list(const std::vector<std::string>& exercise_folders);

json status_json(const std::string& name, const net::ConsoleLink::Station& s);

json event_json(const net::StationEvent& e);

// a figure for the 3D view, to `unit` (a millimetre, a quaternion's 1e-5): the JSON stays short
double rounded(float value, double per_unit);

json vec3_json(const core::Vec3& v);

// A station's (or a replay's) state for a browser: indicators by name; with `view`, the entities' poses (x,
// y, z, qx, qy, qz, qw each, in the scene's order) and the ropes' polylines.
json state_json(const std::string& station, const net::StationState& st, const net::StationScene* scene,
                bool view);

// A station's (or a replay's, or a design's) bulk material for the 3D view: each grid's samples, spacing,
// pose (its corner) and heights above its floor [cm resolution].
json bulk_json(const std::string& station, const net::StationBulk& bulk);

// What a station's 3D view draws: its entities' names, looks and half sizes, once per attempt.
json scene_json(const std::string& station, const net::StationScene& scene);

// The looks (data/visuals/*.yaml) as the browser's 3D view reads them; a container, tyre, shell, hull or mesh
// part is drawn as the box it fills.
json looks_json(const ig::Looks& looks);

json route_json(const training::Route& r);

// What the designer shows of a checked design: its summary, its forms, and its world at the first instant
// drawn by the same 3D view as a station's. Builds the world (throws what building it throws).
json design_preview(const std::string& folder, const DesignCheck& design);

std::string random_token();

std::string hash_password(const std::string& password);

struct Account {
  std::string name, role, trainee;
  bool instructs() const { return role == "administrator" || role == "instructor"; }
  /// A signaller sees the stations live and gives their operators hand signals and radio calls, nothing more.
  bool signals() const { return role == "signaller"; }
};

struct LoginSession {
  Account account;
  std::string csrf;
  Clock::time_point expires;
};

class Console;

// A stored attempt played back in the console: re-simulated from its recording, seeking through keyframes,
// at 0.25-8x; browsers subscribe to it as to a station ("replay-ID").
struct Replay {
  static constexpr int kMostOpen = 4;
  static constexpr std::int64_t kMostStepsPerPoll = 400;  // the server stays responsive while it plays
  std::int64_t id = 0, attempt = 0;                       // attempt: the (first member's) attempt
  std::string session;             // a team session replayed as a whole ("" : one attempt)
  sim::ExerciseSettings exercise;  // the first member's
  std::string recording_file, trainee;
  std::unique_ptr<sim::SessionPlayer> player;  // a single attempt is a session of one
  std::unique_ptr<scene::Snapshot> snapshot = std::make_unique<scene::Snapshot>();
  net::StationScene scene;        // as a station publishes its own
  std::uint64_t scene_names = 0;  // the player's names_version() `scene` was made at
  scene::BulkView bulk;           // its material's heights (tiles copied as they change)
  double speed = 1.0;
  bool playing = false;
  double position_s = 0.0;  // where playing has got to (fractions carried between polls)
  Clock::time_point last_poll = Clock::now();
  std::string owner;
};

// One WebSocket client: the stations' statuses on change, one station's state at up to 10 Hz (the one it
// subscribed to), every event. Writes queue: one at a time on the socket.
// Plain on loopback, TLS on the network: the stream type is LiveSocketOver's.
class LiveSocket : public std::enable_shared_from_this<LiveSocket> {
 public:
  LiveSocket(Console& console, std::string token) : console_(console), token_(std::move(token)) {}
  virtual ~LiveSocket() = default;
  virtual void start(http::request<http::string_body> request) = 0;
  void send(std::string text);
  const std::string& subscribed() const { return station_; }
  /// It draws the 3D view: send it the scene and the entities' poses and ropes with each state.
  bool wants_view() const { return view_; }
  /// The scene it has ("station attempt"), sent once per attempt.
  std::string& scene_sent() { return scene_sent_; }
  /// The bulk surfaces it has ("station count").
  std::string& bulk_sent() { return bulk_sent_; }
  /// The trainee's picture it has ("station count").
  std::string& picture_sent() { return picture_sent_; }
  const std::string& token() const { return token_; }
  bool open() const { return open_; }
  /// Closes it (its login ended).
  virtual void close(const std::string& why) = 0;

 protected:
  void on_message(const std::string& text);
  virtual void write_next() = 0;

  Console& console_;
  std::string token_, station_, scene_sent_, bulk_sent_, picture_sent_;
  bool view_ = false;
  std::deque<std::string> queue_;
  bool writing_ = false, open_ = true;
};

// One HTTP connection (keep-alive): requests in turn, or the upgrade to a LiveSocket.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  virtual ~HttpSession() = default;
  virtual void reply(http::response<http::string_body> response) = 0;
  /// Closes it while it waits on its peer (room for another connection).
  virtual void evict() = 0;
};

struct Connections;

// Who may call an API route or open the live socket (Console::kRoutes). Staff are instructors and
// administrators.
enum class Who : std::uint8_t {
  kAnyone,          ///< no login needed (logging in)
  kAnyAccount,      ///< any account logged in
  kOwnRecords,      ///< staff: anyone's records; a trainee: only their own (?trainee= another is refused)
  kStaff,           ///< instructors and administrators
  kSignallers,      ///< staff and signallers: the stations live, and a signaller's signals and radio calls
  kAdministrators,  ///< administrators only
};

/// Static files: the built front end read once at start, served by exact name (an allow-list: no path from a
/// request is ever joined onto a folder, so no request names a file outside it).
class StaticFiles {
 public:
  static constexpr std::size_t kMostFiles = 256;
  static constexpr std::size_t kMostBytes = std::size_t{64} << 20;
  /// Reads every regular file under `root` (not following links out of it); throws naming what is wrong.
  explicit StaticFiles(const std::string& root);
  struct File {
    std::string content_type, bytes;
  };
  /// The file a request path names ("/" is /index.html), nullptr when it is not one of them.
  const File* find(const std::string& path) const;
  std::size_t size() const { return files_.size(); }

 private:
  std::map<std::string, File> files_;  // by "/relative/path"
};

/// The open HTTP connections, those waiting on their peer the longest first: when the console holds as many
/// as it may, the one idle the longest is closed to make room, so a fresh request is always answered.
struct Connections {
  std::size_t open = 0;
  std::list<std::weak_ptr<HttpSession>> waiting;  ///< on their peer (its next request), longest first
  std::size_t most = 0;                           ///< set at start from the process's file limit
  /// Closes idle connections until there is room for one more.
  void make_room();
  /// Closes the connection idle the longest (the process is out of file descriptors); false: none idle.
  bool evict_oldest();
};

class Console {
 public:
  Console(const ConsoleOptions& options, asio::io_context& io)
      : options_(options),
        io_(io),
        link_(options.name, options.domain),
        db_(options.database),
        audit_(options.database),
        static_files_(options.web_root),
        poll_timer_(io) {
    if (!options.lrs.empty())
      xapi_ = std::make_unique<records::XapiWorker>(
          options.database,
          records::LrsOptions{options.lrs, records::read_lrs_credentials(options.lrs_auth_file),
                              records::xapi_centre(options.centre_iri, options.centre)});
    // a password check for names that have no account, as slow as a real one: the time of a refusal does not
    // tell which names exist
    unknown_account_hash_ = hash_password(random_token());
  }

  ~Console() {
    for (auto& [id, worker] : workers_)
      worker.join();  // its answer then waits in io_, which outlives the console
  }
  Console(const Console&) = delete;
  Console& operator=(const Console&) = delete;
  void start_polling() { poll(); }
  int accounts() { return db_.account_count(); }
  void handle(const http::request<http::string_body>& request, const std::string& peer,
              std::shared_ptr<HttpSession> session);
  /// Why a WebSocket upgrade is refused ("" : it is not), with the status to answer; the socket's login
  /// token in `token`.
  std::string refuse_live(const http::request<http::string_body>& request, http::status& status,
                          std::string& token);
  /// Why the live socket of login `token` may not watch `station` ("" : it may).
  std::string refuse_subscription(const std::string& token, const std::string& station);
  std::optional<Account> account_of(const std::string& token);
  std::string token_of(const http::request<http::string_body>& request) const;
  void attach(std::shared_ptr<LiveSocket> socket) {
    sockets_.push_back(socket);
    socket->send(stations_message());
  }
  std::string stations_message() const;
  const std::shared_ptr<Connections>& connections() const { return connections_; }
  static constexpr std::size_t kMostLiveSockets = 512;
  std::size_t live_sockets() const { return sockets_.size(); }

 private:
  using Response = http::response<http::string_body>;
  /// One API request on its way: what the route table's checks found (its account, whose records it may
  /// see, the id or name in its path).
  struct Call {
    const http::request<http::string_body>& request;
    std::string target, query, peer;
    std::shared_ptr<HttpSession> session;
    std::string token;
    std::optional<Account> account;
    std::string segment;          ///< the path's '*' or '#' segment
    std::int64_t segment_id = 0;  ///< a '#' segment: a positive number
    std::string trainee;          ///< kOwnRecords: whose ("" : everyone's, staff only)
  };
  /// A handler answers now, or later (nullopt: a station's acknowledgement, a thread's work).
  using Handler = std::optional<Response> (Console::*)(Call&);
  struct Route {
    http::verb method;
    std::string_view path;  ///< '*' stands for a path segment (a name), '#' for a positive number
    Who who;
    Handler handler;
  };
  static const Route kRoutes[];
  /// The live socket's upgrade, and each subscription on it: staff only.
  static constexpr Who kLiveSocket = Who::kSignallers;
  /// The route `call` names, its segment filled in (nullptr: none for this method and path).
  static const Route* route_of(Call& call, http::verb method);
  /// Why `who` may not use a route (""; else the reason): role, and for kOwnRecords the trainee asked.
  static std::string refusal(Who who, Call& call);
  /// A trainee account owns only its trainee's records; staff own every record.
  static bool owns(const Account& account, const std::string& trainee) {
    return account.instructs() || account.trainee == trainee;
  }
  /// A browser's request from another origin than the console's own (another site, another port of this
  /// host): "" when it is not one.
  std::string foreign_origin(const http::request<http::string_body>& request) const;

  Response json_reply(const http::request<http::string_body>& request, http::status status,
                      const json& body) const;
  Response error(const http::request<http::string_body>& request, http::status status,
                 const std::string& why) const {
    return json_reply(request, status, {{"error", why}});
  }
  Response file(const http::request<http::string_body>& request) const;
  bool login_blocked(const std::string& key, Clock::time_point now);

  // the resources, one handler each (kRoutes)
  std::optional<Response> login(Call& c);
  std::optional<Response> me(Call& c);
  std::optional<Response> logout(Call& c);
  std::optional<Response> stations(Call& c);
  std::optional<Response> command(Call& c);
  std::optional<Response> team_command(Call& c);
  std::optional<Response> team_start(Call& c);
  std::optional<Response> looks(Call& c);
  std::optional<Response> exercises(Call& c);
  std::optional<Response> commands(Call& c);
  std::optional<Response> teams(Call& c);
  std::optional<Response> xapi_status(Call& c);
  std::optional<Response> trainees(Call& c);
  std::optional<Response> change_trainee(Call& c);
  std::optional<Response> attempts(Call& c);
  std::optional<Response> attempt(Call& c);
  std::optional<Response> attempts_csv_file(Call& c);
  std::optional<Response> trainee_evolution(Call& c);
  std::optional<Response> routes(Call& c);
  std::optional<Response> progress(Call& c);
  std::optional<Response> enrol_or_decide(Call& c);
  std::optional<Response> audit_log(Call& c);
  std::optional<Response> add_account(Call& c);
  std::optional<Response> open_replay(Call& c);
  /// nullopt: a take-over sent to a station, answered when it acknowledges
  std::optional<Response> control_replay(Call& c);
  std::optional<Response> class_overview(Call& c);
  std::optional<Response> compare(Call& c);
  /// The reports (HTML, or PDF printed by chromium beside the console's thread).
  std::optional<Response> report(Call& c);
  /// The exercise designer: GET /api/designer/source?exercise=NAME, POST /api/designer/check {text} (the
  /// loader's verdict, a summary and the scene to preview), POST /api/designer/save {text}.
  std::optional<Response> design_source(Call& c);
  std::optional<Response> check_or_save_design(Call& c);
  /// The route editor: GET /api/routes/source?route=NAME, POST /api/routes/check {id, text} (the route
  /// loader's verdict and the route), POST /api/routes/save {id, text} (into the centre's route folder; the
  /// console's routes reloaded).
  std::optional<Response> route_text(Call& c);
  std::optional<Response> check_or_save_route(Call& c);
  Response save_route_now(const http::request<http::string_body>& request, const std::string& account,
                          const RouteCheck& route, json stages);

  /// A trainee's finished attempts oldest first with score and skills, and where their best score on each
  /// exercise version stands among every trainee's best on it (percentile rank).
  json evolution(const std::string& trainee);
  std::string exercise_folder() const {
    return options_.centre.exercises.empty() ? records::shipped_data_folder() + "/exercises"
                                             : options_.centre.exercises;
  }

  /// What a thread beside the console's gives back: the answer, made on the console's thread.
  using Finish = std::function<Response()>;
  /// Runs `work` on a thread of its own (at most `most` of a kind at once, counted in `running`: a 503
  /// beyond); its Finish answers on the console's thread. Not done within `budget`, the request is answered
  /// 503 at once and the late result dropped.
  void beside(Call& c, int& running, int most, std::chrono::seconds budget, std::function<Finish()> work);
  static constexpr int kMostChecksAtOnce = 2, kMostPrintsAtOnce = 2;
  static constexpr std::chrono::seconds kCheckBudget{10}, kPrintBudget{60};
  int checks_ = 0, printing_ = 0;                   ///< running beside (changed on the console's thread only)
  std::map<std::thread::id, std::thread> workers_;  ///< joined when done, or when the console ends
  std::unique_ptr<records::XapiWorker> xapi_;       ///< the xAPI sender, with --lrs
  /// Attempts (of one trainee or all) as CSV: one row each with the skills; text cells quoted, and
  /// those a spreadsheet would run as a formula prefixed with an apostrophe.
  std::string attempts_csv(const std::optional<std::string>& trainee);
  /// Over TLS the browser sends the session cookie only over TLS.
  std::string secure_cookie() const { return options_.tls_certificate.empty() ? "" : "; Secure"; }
  void poll();

  ConsoleOptions options_;
  asio::io_context& io_;
  net::ConsoleLink link_;
  records::RecordsStore db_;
  records::AuditWriter audit_;  // after db_: the database is made before the writer opens it
  StaticFiles static_files_;
  std::shared_ptr<Connections> connections_ = std::make_shared<Connections>();
  asio::steady_timer poll_timer_;
  std::string unknown_account_hash_;
  std::map<std::string, LoginSession> sessions_;
  std::map<std::string, std::deque<Clock::time_point>> login_failures_;
  struct Pending {
    http::request<http::string_body> request;
    std::shared_ptr<HttpSession> session;
    Account account;
    std::string station, kind;
    Clock::time_point deadline;
  };
  std::map<std::uint64_t, Pending> pending_;
  // a command to every running member of a team session: answered when every member has (or 3 s have passed)
  struct TeamPending {
    http::request<http::string_body> request;
    std::shared_ptr<HttpSession> session;
    Account account;
    std::string team, kind;
    std::vector<std::pair<std::uint64_t, std::string>> sent;  // command id, station
    std::map<std::string, net::CommandAck> answers;           // by station
    Clock::time_point deadline;
  };
  std::vector<TeamPending> team_pending_;
  std::vector<std::pair<std::uint64_t, Clock::time_point>> watches_;  // watch commands awaiting their ack
  Clock::time_point next_watch_{};
  std::vector<std::shared_ptr<LiveSocket>> sockets_;
  Clock::time_point next_state_push_{}, next_stations_push_{};
  bool stations_changed_ = false;
  std::map<std::int64_t, Replay> replays_;
  std::int64_t next_replay_ = 1;
  void play_replays(Clock::time_point now);
  json replay_state(Replay& replay, bool view = false);
  /// Sends a socket its subscription's scene (when it draws the 3D view and has not got this attempt's)
  /// and state.
  /// `scene_count`: how many scenes the station has sent (a renamed entity's attempt is sent again).
  void push_state(LiveSocket& socket, const std::string& station, const net::StationScene* scene,
                  std::uint64_t scene_count, const std::function<json(bool)>& state_of);
  std::string looks_ =
      dump(looks_json(ig::load_shipped_looks(records::shipped_data_folder(), sim::machine_kinds())));
  /// the training routes (the centre's and data/routes), checked at start: a bad one stops the console
  /// naming it
  std::vector<training::Route> routes_ = records::load_centre_routes(centre());
  /// the centre's folders, the designer's folder being the centre's exercise folder
  records::CentreFolders centre() const { return {exercise_folder(), options_.centre.routes}; }
};

}  // namespace harbour::console
