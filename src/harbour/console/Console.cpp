// The instructor console's server: static files, the JSON API and the live WebSocket, over Boost.Beast
// (kept in this one translation unit: Beast is slow to compile). One thread runs everything: the HTTP and
// WebSocket sessions, the records database and the DDS link, polled every few milliseconds.
#include "harbour/console/Console.h"

#include <sodium.h>
#include <sys/resource.h>
#include <unistd.h>

#include <utility>  // before Boost.Asio 1.74, which uses std::exchange without it

#include <openssl/err.h>
#include <openssl/x509.h>
#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/console/Designer.h"
#include "harbour/core/Text.h"
#include "harbour/ig/Visuals.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/io/TeamFiles.h"
#include "harbour/machines/MachineType.h"
#include "harbour/net/DdsLink.h"
#include "harbour/records/AuditWriter.h"
#include "harbour/records/CentreRoutes.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/records/Reports.h"
#include "harbour/records/XapiSender.h"
#include "harbour/sim/Recording.h"
#include "harbour/station/ConsolePresence.h"
#include "harbour/training/Figures.h"

namespace harbour::console {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using json = nlohmann::json;

// a stored figure's words, for a page to label it and show it in its unit (shown = stored × scale)
json figure_words_json(const std::string& name) {
  const training::FigureWords w = training::figure_words(name);
  return {{"label", w.label}, {"unit", w.unit}, {"scale", w.scale}, {"about", w.about}};
}

// an attempt's event: when, what (the stored kind and value) and in words
json attempt_event_json(double at_s, const std::string& kind, double value) {
  return {{"at_s", at_s}, {"kind", kind}, {"value", value}, {"text", training::event_text(kind, value)}};
}

using Clock = std::chrono::steady_clock;

constexpr std::size_t kMaxBodyBytes = 64 * 1024;     // the API's requests are small
constexpr std::size_t kMaxSocketMessage = 4 * 1024;  // a browser's WebSocket messages are smaller still
// a connection's request (or the TLS handshake) must arrive within this: an idle keep-alive connection closes
constexpr auto kRequestTimeout = std::chrono::seconds(30);
// file descriptors kept free of HTTP connections (the records database, the DDS link, live sockets, threads)
constexpr std::size_t kReservedFiles = 1024;
constexpr int kMaxJsonDepth = 8;
constexpr auto kSessionLifetime = std::chrono::hours(12);
constexpr auto kAckTimeout = std::chrono::seconds(3);
constexpr int kLoginFailuresAllowed = 5;  // per minute, per address and per account
constexpr auto kLoginWindow = std::chrono::seconds(60);

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_console_signal(int) {
  g_stop = 1;
}

std::string random_token() {
  unsigned char bytes[32];
  randombytes_buf(bytes, sizeof bytes);
  char hex[sizeof bytes * 2 + 1];
  sodium_bin2hex(hex, sizeof hex, bytes, sizeof bytes);
  return hex;
}

std::string hash_password(const std::string& password) {
  char hash[crypto_pwhash_STRBYTES];
  if (crypto_pwhash_str(hash, password.data(), password.size(), crypto_pwhash_OPSLIMIT_INTERACTIVE,
                        crypto_pwhash_MEMLIMIT_INTERACTIVE) != 0)
    throw std::runtime_error("hashing the password: out of memory");
  return hash;
}

// how deep `text` nests arrays and objects (outside strings): refused before parsing when too deep
int json_depth(const std::string& text) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{')
      deepest = std::max(deepest, ++depth);
    else if (c == ']' || c == '}')
      --depth;
  }
  return deepest;
}

// a query parameter's value, percent-decoded ('+' a space); "" when absent or not decodable
std::string query_param(const std::string& query, const std::string& key) {
  std::size_t start = 0;
  while (start <= query.size()) {
    const std::size_t end = std::min(query.find('&', start), query.size());
    const std::string pair = query.substr(start, end - start);
    if (pair.rfind(key + "=", 0) == 0) {
      std::string value;
      for (std::size_t i = key.size() + 1; i < pair.size(); ++i) {
        if (pair[i] == '+') {
          value += ' ';
        } else if (pair[i] == '%') {
          if (i + 2 >= pair.size() || !std::isxdigit(static_cast<unsigned char>(pair[i + 1])) ||
              !std::isxdigit(static_cast<unsigned char>(pair[i + 2])))
            return "";
          value += static_cast<char>(std::stoi(pair.substr(i + 1, 2), nullptr, 16));
          i += 2;
        } else {
          value += pair[i];
        }
      }
      return value;
    }
    start = end + 1;
  }
  return "";
}

// a JSON object from a request or message body, or why not: too deep, not JSON, not an object, or an object
// that gives a key twice (parsers disagree on which one counts: the last here, the first elsewhere)
std::optional<json> parse_object(const std::string& text, std::string& why) {
  if (json_depth(text) > kMaxJsonDepth) {
    why = "JSON nested too deep";
    return std::nullopt;
  }
  std::vector<std::set<std::string>> keys;  // of each object open at this point
  std::string duplicate;
  const json::parser_callback_t watch = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) {
      keys.emplace_back();
    } else if (event == json::parse_event_t::object_end) {
      if (!keys.empty()) keys.pop_back();
    } else if (event == json::parse_event_t::key && !keys.empty() && parsed.is_string() &&
               !keys.back().insert(parsed.get<std::string>()).second && duplicate.empty()) {
      duplicate = parsed.get<std::string>();
    }
    return true;
  };
  json value = json::parse(text, watch, false);
  if (value.is_discarded() || !value.is_object()) {
    why = "the body is not a JSON object";
    return std::nullopt;
  }
  if (!duplicate.empty()) {
    why = "key '" + core::printable(duplicate, 64) + "' is given twice";
    return std::nullopt;
  }
  return value;
}

// a string field of at most `longest` bytes with no control or bidirectional formatting characters (a
// password: no control characters); "" and a reason when missing or bad
std::optional<std::string> text_field(const json& body, const char* field, std::size_t longest,
                                      std::string& why, bool required = true, bool password = false) {
  const auto found = body.find(field);
  if (found == body.end() || found->is_null()) {
    if (required) why = std::string("field '") + field + "' is missing";
    return required ? std::nullopt : std::optional<std::string>("");
  }
  if (!found->is_string()) {
    why = std::string("field '") + field + "' is not a string";
    return std::nullopt;
  }
  const std::string value = found->get<std::string>();
  if (value.size() > longest) {
    why = std::string("field '") + field + "' is longer than " + std::to_string(longest) + " bytes";
    return std::nullopt;
  }
  if (password) {
    for (const unsigned char c : value)
      if (c < 0x20 || c == 0x7f) {
        why = std::string("field '") + field + "' holds control characters";
        return std::nullopt;
      }
  } else if (const std::string bad = core::why_bad_name(value, longest); !value.empty() && !bad.empty()) {
    why = std::string("field '") + field + "' " + bad;
    return std::nullopt;
  }
  return value;
}

// JSON text; strings that are not UTF-8 (a foreign DDS peer's, a database's) are repaired, not thrown on
std::string dump(const json& value) {
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string content_type(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".svg") return "image/svg+xml";
  return "application/octet-stream";
}

// The shipped team sessions (data/teams) and their roles; a team file in error is listed with its error.
json team_list(const std::vector<std::string>& exercise_folders) {
  json list = json::array();
  std::set<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& f : std::filesystem::directory_iterator(records::shipped_data_folder() + "/teams", ec))
    if (f.path().extension() == ".yaml") files.insert(f.path());
  for (const std::filesystem::path& file : files) {
    try {
      const io::Team team = io::load_team(file.string(), exercise_folders);
      json roles = json::array();
      for (const io::TeamRole& r : team.roles)
        roles.push_back(
            {{"role", r.role}, {"exercise", std::filesystem::path(r.exercise_file).stem().string()}});
      list.push_back({{"name", team.name}, {"roles", roles}});
    } catch (const std::exception& e) {
      list.push_back({{"name", file.stem().string()}, {"error", e.what()}});
    }
  }
  return list;
}

json status_json(const std::string& name, const net::ConsoleLink::Station& s) {
  const net::StationStatus& st = s.status;
  return {{"station", name},
          {"host", st.host().to_string()},
          {"state", s.gone   ? "offline"
                    : s.lost ? "lost"
                             : st.state().to_string()},
          {"machine", st.machine().to_string()},
          {"exercise", st.exercise().to_string()},
          {"trainee", st.trainee().to_string()},
          {"attempt", st.attempt()},
          {"time_s", st.time_s()},
          {"time_limit_s", st.time_limit_s()},
          {"real_time_factor", st.real_time_factor()},
          {"late_ticks", st.late_ticks()},
          {"skipped_ticks", st.skipped_ticks()},
          {"keeping_real_time", st.keeping_real_time()},
          {"devices_missing", st.devices_missing()},
          {"physics_warnings", st.physics_warnings()},
          {"diverged", st.diverged()},
          {"score", st.score()},
          {"moves_done", st.moves_done()},
          {"moves_total", st.moves_total()},
          {"collisions", st.collisions()},
          {"message", st.message().to_string()},
          {"team", st.team().to_string()},
          {"role", st.role().to_string()},
          {"states_received", s.state_count}};
}

json event_json(const net::StationEvent& e) {
  return {{"type", "event"},
          {"station", e.station().to_string()},
          {"attempt", e.attempt()},
          {"time_s", e.time_s()},
          {"kind", e.kind().to_string()},
          {"value", e.value()},
          {"text", e.text().to_string()},
          {"words", training::event_text(e.kind().to_string(), e.value(), e.text().to_string())}};
}

// a figure for the 3D view, to `unit` (a millimetre, a quaternion's 1e-5): the JSON stays short
double rounded(float value, double per_unit) {
  return std::round(static_cast<double>(value) * per_unit) / per_unit;
}

json vec3_json(const core::Vec3& v) {
  return {v.x, v.y, v.z};
}

// A station's (or a replay's) state for a browser: indicators by name; with `view`, the entities' poses (x,
// y, z, qx, qy, qz, qw each, in the scene's order) and the ropes' polylines.
json state_json(const std::string& station, const net::StationState& st, const net::StationScene* scene,
                bool view) {
  json indicators = json::object();
  if (scene)
    for (std::size_t n = 0; n < st.indicators().size() && n < scene->indicator_names().size(); ++n)
      indicators[scene->indicator_names()[n].to_string()] = st.indicators()[n];
  json state{{"type", "state"},
             {"station", station},
             {"attempt", st.attempt()},
             {"time_s", st.time_s()},
             {"held", st.held()},
             {"wind_mps", {st.wind_mps()[0], st.wind_mps()[1], st.wind_mps()[2]}},
             {"time_of_day_h", st.time_of_day_h()},
             {"visibility_m", st.visibility_m()},
             {"rain_mm_per_h", st.rain_mm_per_h()},
             {"indicators", indicators}};
  if (!view) return state;
  json poses = json::array();
  for (std::size_t n = 0; n < st.entity_poses().size(); ++n)
    poses.push_back(rounded(st.entity_poses()[n], n % 7 < 3 ? 1e3 : 1e5));
  json points = json::array();
  for (const float v : st.rope_points_m())
    points.push_back(rounded(v, 1e3));
  state["water_level_m"] = st.water_level_m();
  state["poses"] = std::move(poses);
  state["ropes"] = {{"counts", st.rope_point_counts()}, {"points", std::move(points)}};
  return state;
}

// A station's (or a replay's, or a design's) bulk material for the 3D view: each grid's samples, spacing,
// pose (its corner) and heights above its floor [cm resolution].
json bulk_json(const std::string& station, const net::StationBulk& bulk) {
  json grids = json::array();
  std::size_t first = 0;
  for (std::size_t g = 0; g < bulk.samples_x().size() && g < bulk.samples_y().size() &&
                          g < bulk.sample_m().size() && 7 * g + 7 <= bulk.grid_poses().size();
       ++g) {
    const std::size_t count = std::size_t{bulk.samples_x()[g]} * bulk.samples_y()[g];
    if (first + count > bulk.heights_m().size()) break;  // a damaged sample: what is whole
    json heights = json::array();
    for (std::size_t k = first; k < first + count; ++k)
      heights.push_back(rounded(bulk.heights_m()[k], 1e2));
    first += count;
    json pose = json::array();
    for (std::size_t k = 7 * g; k < 7 * g + 7; ++k)
      pose.push_back(rounded(bulk.grid_poses()[k], 1e4));
    grids.push_back({{"nx", bulk.samples_x()[g]},
                     {"ny", bulk.samples_y()[g]},
                     {"step_m", bulk.sample_m()[g]},
                     {"pose", std::move(pose)},
                     {"heights", std::move(heights)}});
  }
  return {{"type", "bulk"},
          {"station", station},
          {"attempt", bulk.attempt()},
          {"time_s", bulk.time_s()},
          {"grids", std::move(grids)}};
}

// What a station's 3D view draws: its entities' names, looks and half sizes, once per attempt.
json scene_json(const std::string& station, const net::StationScene& scene) {
  json entities = json::array();
  const auto& extents = scene.entity_half_extents_m();
  for (std::size_t n = 0; n < scene.entity_names().size() && n < scene.entity_visuals().size(); ++n)
    entities.push_back(
        {{"name", scene.entity_names()[n].to_string()},
         {"visual", scene.entity_visuals()[n].to_string()},
         {"half_m", 3 * n + 2 < extents.size() ? json{extents[3 * n], extents[3 * n + 1], extents[3 * n + 2]}
                                               : json{0.5, 0.5, 0.5}}});
  return {{"type", "scene"},
          {"station", station},
          {"attempt", scene.attempt()},
          {"machine", scene.machine().to_string()},
          {"entities", std::move(entities)}};
}

// The looks (data/visuals/*.yaml) as the browser's 3D view reads them; a container, tyre, shell, hull or mesh
// part is drawn as the box it fills.
json looks_json(const ig::Looks& looks) {
  json visuals = json::object();
  for (const auto& [key, visual] : looks.visuals) {
    json parts = json::array();
    for (const ig::VisualPart& part : visual.parts) {
      static constexpr const char* kShapes[] = {"box",   "lattice", "container", "tyre",
                                                "shell", "hull",    "mesh"};
      static_assert(std::size(kShapes) == static_cast<std::size_t>(ig::VisualPart::Shape::kMesh) + 1);
      parts.push_back({{"shape", kShapes[static_cast<int>(part.shape)]},
                       {"size_m", part.size_m ? vec3_json(*part.size_m) : json(nullptr)},
                       {"at_m", vec3_json(part.centre_m)},
                       {"color", vec3_json(part.color)},
                       {"livery", part.livery},
                       {"bay_m", part.bay_m},
                       {"member_m", part.member_m}});
    }
    json liveries = json::array();
    for (const core::Vec3& c : visual.liveries)
      liveries.push_back(vec3_json(c));
    visuals[key] = {{"parts", std::move(parts)}, {"liveries", std::move(liveries)}};
  }
  json scenery = json::array();
  for (const ig::SceneryPart& part : looks.scenery)
    scenery.push_back({{"shape", part.shape == ig::SceneryPart::Shape::kBox ? "box" : "cylinder"},
                       {"at_m", vec3_json(part.centre_m)},
                       {"size_m", vec3_json(part.size_m)},
                       {"color", vec3_json(part.color)},
                       {"repeat", part.repeat},
                       {"step_m", vec3_json(part.step_m)}});
  // the trainee's HUD lines: the console's live line shows the station's indicators as the cab shows them
  json hud = json::array();
  for (const ig::HudItem& h : looks.hud)
    hud.push_back({{"indicator", h.indicator},
                   {"label", h.label},
                   {"unit", h.unit},
                   {"decimals", h.decimals},
                   {"lamp", h.lamp},
                   {"scale", h.scale},
                   {"words", h.words},
                   {"words_from", h.words_from},
                   {"shown_while", h.shown_while},
                   {"machines", h.machines}});
  return {{"visuals", std::move(visuals)}, {"scenery", std::move(scenery)}, {"hud", std::move(hud)}};
}

struct Account {
  std::string name, role, trainee;
  bool instructs() const { return role == "administrator" || role == "instructor"; }
};

struct LoginSession {
  Account account;
  std::string csrf;
  Clock::time_point expires;
};

class Console;

json route_json(const training::Route& r) {
  json stages = json::array();
  for (const training::Stage& s : r.stages) {
    json bounds = json::array();
    for (const training::MetricBound& b : s.bounds)
      bounds.push_back({{"metric", b.metric},
                        {"min", b.min ? json(*b.min) : json(nullptr)},
                        {"max", b.max ? json(*b.max) : json(nullptr)}});
    stages.push_back({{"id", s.id},
                      {"goal", s.goal},
                      {"exercise", s.exercise},
                      {"min_score", s.min_score ? json(*s.min_score) : json(nullptr)},
                      {"bounds", bounds},
                      {"repetitions", s.repetitions},
                      {"max_attempts", s.max_attempts},
                      {"requires", s.requires_stages}});
  }
  return {{"id", r.id}, {"name", r.name}, {"machine", r.machine}, {"stages", stages}};
}

// What the designer shows of a checked design: its summary, its forms, and its world at the first instant
// drawn by the same 3D view as a station's. Builds the world (throws what building it throws).
json design_preview(const std::string& folder, const DesignCheck& design) {
  const sim::Simulation simulation(design.exercise.scenario);
  auto snapshot = std::make_unique<scene::Snapshot>();
  simulation.write_snapshot(*snapshot);
  const net::StationScene published = net::scene_message(simulation.scene(), 0);
  json bulk;
  if (const bulk::BulkWorld* material = simulation.bulk()) {
    scene::BulkView view;
    bulk::publish(*material, view);
    bulk = bulk_json("designer", net::bulk_message(view, 0, 0.0));
  }
  const sim::ExerciseSettings& x = design.exercise;
  return {
      {"exercise", x.name},
      {"machine", x.scenario.machine.kind()},
      {"version", design.version},
      {"containers", x.scenario.containers.size()},
      {"moves", x.moves.size()},
      {"events", x.scenario.events.size() + x.scenario.lift_events.size()},
      {"time_limit_s", x.rules.time_limit_s},
      {"pass_score", x.rules.pass_score},
      {"wind_mps", x.scenario.weather.wind_mean_mps},
      {"form", design_form(folder, design)},
      {"scene", scene_json("designer", published)},
      {"state", state_json("designer", net::state_message(*snapshot, simulation.scene().entities.size(), 0),
                           &published, true)},
      {"bulk", bulk}};
}

// A stored attempt played back in the console: re-simulated from its recording, seeking through keyframes,
// at 0.25-8x; browsers subscribe to it as to a station ("replay-ID").
struct Replay {
  static constexpr int kMostOpen = 4;
  static constexpr std::int64_t kMostStepsPerPoll = 400;  // the server stays responsive while it plays
  std::int64_t id = 0, attempt = 0;
  sim::ExerciseSettings exercise;
  sim::Recording recording;
  std::string recording_file, trainee;
  std::unique_ptr<sim::ReplayPlayer> player;
  std::unique_ptr<scene::Snapshot> snapshot = std::make_unique<scene::Snapshot>();
  net::StationScene scene;  // as a station publishes its own
  scene::BulkView bulk;     // its material's heights (tiles copied as they change)
  double speed = 1.0;
  bool playing = false;
  double position_steps = 0.0;  // where playing has got to (fractions carried between polls)
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

using TlsStream = beast::ssl_stream<beast::tcp_stream>;
template <class Stream>
constexpr bool kTls = std::is_same_v<Stream, TlsStream>;

template <class Stream>
class LiveSocketOver final : public LiveSocket {
 public:
  LiveSocketOver(Stream stream, Console& console, std::string token)
      : LiveSocket(console, std::move(token)), ws_(std::move(stream)) {}
  void start(http::request<http::string_body> request) override;
  void close(const std::string& why) override;

 private:
  void read();
  void write_next() override;
  std::shared_ptr<LiveSocketOver> self() {
    return std::static_pointer_cast<LiveSocketOver>(shared_from_this());
  }

  websocket::stream<Stream> ws_;
  beast::flat_buffer buffer_;
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

template <class Stream>
class HttpConnection final : public HttpSession {
 public:
  HttpConnection(Stream stream, Console& console);
  ~HttpConnection() override;
  /// Reads the first request (after the TLS handshake on a TLS connection).
  void start();
  void reply(http::response<http::string_body> response) override;
  void evict() override;

 private:
  void read();
  void on_request();
  void shut();
  /// It waits on its peer (listed as idle, the oldest evicted first), or no longer.
  void waiting(bool on_peer);
  std::shared_ptr<HttpConnection> self() {
    return std::static_pointer_cast<HttpConnection>(shared_from_this());
  }

  Stream stream_;
  Console& console_;
  std::shared_ptr<Connections> connections_;
  std::optional<std::list<std::weak_ptr<HttpSession>>::iterator> waiting_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  bool keep_alive_ = false;
};

// Who may call an API route or open the live socket (Console::kRoutes). Staff are instructors and
// administrators.
enum class Who : std::uint8_t {
  kAnyone,          ///< no login needed (logging in)
  kAnyAccount,      ///< any account logged in
  kOwnRecords,      ///< staff: anyone's records; a trainee: only their own (?trainee= another is refused)
  kStaff,           ///< instructors and administrators
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
  static constexpr Who kLiveSocket = Who::kStaff;
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
  std::optional<Response> looks(Call& c);
  std::optional<Response> exercises(Call& c);
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
  void push_state(LiveSocket& socket, const std::string& station, const net::StationScene* scene,
                  const std::function<json(bool)>& state_of);
  std::string looks_ =
      dump(looks_json(ig::load_looks(records::shipped_data_folder() + "/visuals/harbour.yaml")));
  /// the training routes (the centre's and data/routes), checked at start: a bad one stops the console
  /// naming it
  std::vector<training::Route> routes_ = records::load_centre_routes(centre());
  /// the centre's folders, the designer's folder being the centre's exercise folder
  records::CentreFolders centre() const { return {exercise_folder(), options_.centre.routes}; }
};

// Every API route and who may call it: read this table to know what each role can see and do.
const Console::Route Console::kRoutes[] = {
    {http::verb::post, "/api/login", Who::kAnyone, &Console::login},
    {http::verb::get, "/api/me", Who::kAnyAccount, &Console::me},
    {http::verb::post, "/api/logout", Who::kAnyAccount, &Console::logout},
    {http::verb::get, "/api/looks", Who::kAnyAccount, &Console::looks},
    {http::verb::get, "/api/exercises", Who::kAnyAccount, &Console::exercises},
    {http::verb::get, "/api/teams", Who::kStaff, &Console::teams},
    {http::verb::post, "/api/teams/*/command", Who::kStaff, &Console::team_command},
    {http::verb::get, "/api/routes", Who::kAnyAccount, &Console::routes},
    {http::verb::get, "/api/attempts", Who::kOwnRecords, &Console::attempts},
    {http::verb::get, "/api/attempts/#", Who::kOwnRecords, &Console::attempt},
    {http::verb::get, "/api/attempts.csv", Who::kOwnRecords, &Console::attempts_csv_file},
    {http::verb::get, "/api/evolution", Who::kOwnRecords, &Console::trainee_evolution},
    {http::verb::get, "/api/progress", Who::kOwnRecords, &Console::progress},
    {http::verb::get, "/api/reports/trainee", Who::kOwnRecords, &Console::report},
    {http::verb::get, "/api/reports/trainee.pdf", Who::kOwnRecords, &Console::report},
    {http::verb::get, "/api/stations", Who::kStaff, &Console::stations},
    {http::verb::post, "/api/stations/*/command", Who::kStaff, &Console::command},
    {http::verb::get, "/api/xapi", Who::kStaff, &Console::xapi_status},
    {http::verb::get, "/api/trainees", Who::kStaff, &Console::trainees},
    {http::verb::post, "/api/trainees", Who::kStaff, &Console::change_trainee},
    {http::verb::patch, "/api/trainees", Who::kStaff, &Console::change_trainee},
    {http::verb::post, "/api/enrolments", Who::kStaff, &Console::enrol_or_decide},
    {http::verb::post, "/api/decisions", Who::kStaff, &Console::enrol_or_decide},
    {http::verb::get, "/api/audit", Who::kStaff, &Console::audit_log},
    {http::verb::post, "/api/replays", Who::kStaff, &Console::open_replay},
    {http::verb::post, "/api/replays/#", Who::kStaff, &Console::control_replay},
    {http::verb::get, "/api/class", Who::kStaff, &Console::class_overview},
    {http::verb::get, "/api/compare", Who::kStaff, &Console::compare},
    {http::verb::get, "/api/reports/class", Who::kStaff, &Console::report},
    {http::verb::get, "/api/reports/class.pdf", Who::kStaff, &Console::report},
    {http::verb::get, "/api/designer/source", Who::kStaff, &Console::design_source},
    {http::verb::post, "/api/designer/check", Who::kStaff, &Console::check_or_save_design},
    {http::verb::post, "/api/designer/save", Who::kStaff, &Console::check_or_save_design},
    {http::verb::get, "/api/routes/source", Who::kStaff, &Console::route_text},
    {http::verb::post, "/api/routes/check", Who::kStaff, &Console::check_or_save_route},
    {http::verb::post, "/api/routes/save", Who::kStaff, &Console::check_or_save_route},
    {http::verb::post, "/api/accounts", Who::kAdministrators, &Console::add_account},
};

// ---------------------------------------------------------------------------------------------------
// HTTP

template <class Stream>
HttpConnection<Stream>::HttpConnection(Stream stream, Console& console)
    : stream_(std::move(stream)), console_(console), connections_(console.connections()) {
  ++connections_->open;
}

template <class Stream>
HttpConnection<Stream>::~HttpConnection() {
  waiting(false);
  --connections_->open;
}

template <class Stream>
void HttpConnection<Stream>::waiting(bool on_peer) {
  if (waiting_) connections_->waiting.erase(*waiting_);
  waiting_.reset();
  if (on_peer) waiting_ = connections_->waiting.insert(connections_->waiting.end(), weak_from_this());
}

template <class Stream>
void HttpConnection<Stream>::evict() {
  waiting_.reset();  // the list has let go of it
  beast::error_code ignored;
  beast::get_lowest_layer(stream_).socket().close(ignored);  // its wait ends (operation aborted)
}

template <class Stream>
void HttpConnection<Stream>::start() {
  if constexpr (kTls<Stream>) {
    waiting(true);
    beast::get_lowest_layer(stream_).expires_after(kRequestTimeout);
    stream_.async_handshake(asio::ssl::stream_base::server, [self = self()](beast::error_code ec) {
      self->waiting(false);
      if (ec) return self->shut();  // not TLS, or a certificate the browser refused: nothing to answer
      self->read();
    });
  } else {
    read();
  }
}

template <class Stream>
void HttpConnection<Stream>::shut() {
  waiting(false);
  beast::error_code ignored;
  beast::get_lowest_layer(stream_).socket().shutdown(tcp::socket::shutdown_both, ignored);
}

template <class Stream>
void HttpConnection<Stream>::read() {
  parser_.emplace();
  parser_->body_limit(kMaxBodyBytes);
  parser_->header_limit(16 * 1024);
  beast::get_lowest_layer(stream_).expires_after(kRequestTimeout);
  waiting(true);
  http::async_read(stream_, buffer_, *parser_, [self = self()](beast::error_code ec, std::size_t) {
    self->waiting(false);
    if (ec == http::error::end_of_stream || ec == beast::error::timeout || ec == asio::error::eof ||
        ec == asio::ssl::error::stream_truncated || ec == asio::error::operation_aborted ||
        ec == asio::error::bad_descriptor) {
      self->shut();
      return;
    }
    if (ec) {
      // a malformed or oversized request: a clear 4xx, then the connection closes
      http::response<http::string_body> r{ec == http::error::body_limit || ec == http::error::header_limit
                                              ? http::status::payload_too_large
                                              : http::status::bad_request,
                                          11};
      r.set(http::field::content_type, "application/json");
      r.body() = dump(json{{"error", "bad request: " + ec.message()}});
      r.keep_alive(false);
      r.prepare_payload();
      self->keep_alive_ = false;
      self->reply(std::move(r));
      return;
    }
    self->on_request();
  });
}

template <class Stream>
void HttpConnection<Stream>::on_request() {
  http::request<http::string_body> request = parser_->release();
  keep_alive_ = request.keep_alive();
  beast::error_code ec;
  const tcp::endpoint peer = beast::get_lowest_layer(stream_).socket().remote_endpoint(ec);
  const std::string address = ec ? "?" : peer.address().to_string();
  if (websocket::is_upgrade(request)) {
    std::string token;
    http::status status = http::status::ok;
    if (const std::string why = console_.refuse_live(request, status, token); !why.empty()) {
      http::response<http::string_body> r{status, request.version()};
      r.set(http::field::content_type, "application/json");
      r.body() = dump(json{{"error", why}});
      r.keep_alive(false);
      r.prepare_payload();
      keep_alive_ = false;
      reply(std::move(r));
      return;
    }
    beast::get_lowest_layer(stream_).expires_never();
    auto socket = std::make_shared<LiveSocketOver<Stream>>(std::move(stream_), console_, token);
    socket->start(std::move(request));
    return;
  }
  console_.handle(request, address, shared_from_this());
}

template <class Stream>
void HttpConnection<Stream>::reply(http::response<http::string_body> response) {
  auto shared = std::make_shared<http::response<http::string_body>>(std::move(response));
  shared->keep_alive(keep_alive_ && shared->keep_alive());
  http::async_write(stream_, *shared, [self = self(), shared](beast::error_code ec, std::size_t) {
    if (ec || !shared->keep_alive()) {
      self->shut();
      return;
    }
    self->read();
  });
}

// ---------------------------------------------------------------------------------------------------
// WebSocket

template <class Stream>
void LiveSocketOver<Stream>::start(http::request<http::string_body> request) {
  ws_.read_message_max(kMaxSocketMessage);
  ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  ws_.async_accept(request, [self = self()](beast::error_code ec) {
    if (ec) {
      self->open_ = false;
      return;
    }
    self->console_.attach(self);
    self->read();
  });
}

template <class Stream>
void LiveSocketOver<Stream>::read() {
  ws_.async_read(buffer_, [self = self()](beast::error_code ec, std::size_t) {
    if (ec == websocket::error::message_too_big) {
      self->open_ = false;
      self->ws_.async_close({websocket::close_code::too_big, "message over 4 KiB"},
                            [self](beast::error_code) {});
      return;
    }
    if (ec) {
      self->open_ = false;
      return;
    }
    const std::string text = beast::buffers_to_string(self->buffer_.data());
    self->buffer_.consume(self->buffer_.size());
    self->on_message(text);
    self->read();
  });
}

void LiveSocket::on_message(const std::string& text) {
  std::string why;
  const std::optional<json> message = parse_object(text, why);
  if (!message) {
    send(dump(json{{"type", "error"}, {"error", why}}));
    return;
  }
  const std::optional<std::string> type = text_field(*message, "type", 32, why);
  if (!type) {
    send(dump(json{{"type", "error"}, {"error", why}}));
    return;
  }
  if (*type == "subscribe") {
    const std::optional<std::string> station = text_field(*message, "station", 64, why, false);
    if (!station) {
      send(dump(json{{"type", "error"}, {"error", why}}));
      return;
    }
    const auto view = message->find("view");
    if (view != message->end() && !view->is_boolean()) {
      send(dump(json{{"type", "error"}, {"error", "field 'view': true or false"}}));
      return;
    }
    if (const std::string refused = console_.refuse_subscription(token_, *station); !refused.empty()) {
      send(dump(json{{"type", "error"}, {"error", "subscription refused: " + refused}}));
      return;
    }
    station_ = *station;
    view_ = view != message->end() && view->get<bool>();
    scene_sent_.clear();
    send(dump(json{{"type", "subscribed"}, {"station", station_}, {"view", view_}}));
    return;
  }
  send(dump(json{{"type", "error"}, {"error", "unknown message type '" + core::printable(*type) + "'"}}));
}

template <class Stream>
void LiveSocketOver<Stream>::close(const std::string& why) {
  if (!open_) return;
  open_ = false;
  ws_.async_close({websocket::close_code::policy_error, why}, [self = self()](beast::error_code) {});
}

void LiveSocket::send(std::string text) {
  if (!open_) return;
  if (queue_.size() > 64) queue_.pop_front();  // a slow browser loses old states, not the console
  queue_.push_back(std::move(text));
  if (!writing_) write_next();
}

template <class Stream>
void LiveSocketOver<Stream>::write_next() {
  if (queue_.empty() || !open_) {
    writing_ = false;
    return;
  }
  writing_ = true;
  ws_.text(true);
  ws_.async_write(asio::buffer(queue_.front()), [self = self()](beast::error_code ec, std::size_t) {
    self->queue_.pop_front();
    if (ec) {
      self->open_ = false;
      self->writing_ = false;
      return;
    }
    self->write_next();
  });
}

// ---------------------------------------------------------------------------------------------------
// The console

std::string Console::token_of(const http::request<http::string_body>& request) const {
  const auto cookie = request.find(http::field::cookie);
  if (cookie == request.end()) return "";
  const std::string header(cookie->value());
  std::size_t at = 0;
  while (at < header.size()) {
    const std::size_t end = std::min(header.find(';', at), header.size());
    std::string pair = header.substr(at, end - at);
    while (!pair.empty() && pair.front() == ' ')
      pair.erase(0, 1);
    if (pair.rfind("hs_session=", 0) == 0) return pair.substr(11);
    at = end + 1;
  }
  return "";
}

std::optional<Account> Console::account_of(const std::string& token) {
  const auto found = sessions_.find(token);
  if (token.empty() || found == sessions_.end()) return std::nullopt;
  if (Clock::now() > found->second.expires) {
    sessions_.erase(found);
    return std::nullopt;
  }
  return found->second.account;
}

Console::Response Console::json_reply(const http::request<http::string_body>& request, http::status status,
                                      const json& body) const {
  Response r{status, request.version()};
  r.set(http::field::content_type, "application/json");
  r.set(http::field::cache_control, "no-store");
  r.set("X-Content-Type-Options", "nosniff");
  r.body() = dump(body);
  r.keep_alive(request.keep_alive());
  r.prepare_payload();
  return r;
}

Console::Response Console::file(const http::request<http::string_body>& request) const {
  const std::string target(request.target().substr(0, request.target().find('?')));
  const StaticFiles::File* found = static_files_.find(target);
  if (!found) return error(request, http::status::not_found, "no such page");
  Response r{http::status::ok, request.version()};
  r.set(http::field::content_type, found->content_type);
  r.set("X-Content-Type-Options", "nosniff");
  r.set("Content-Security-Policy",
        "default-src 'self'; connect-src 'self'; img-src 'self' data:; style-src 'self' 'unsafe-inline'");
  r.body() = found->bytes;
  r.keep_alive(request.keep_alive());
  r.prepare_payload();
  if (request.method() == http::verb::head) r.body().clear();
  return r;
}

StaticFiles::StaticFiles(const std::string& root) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path base = fs::canonical(root, ec);
  if (ec) throw std::runtime_error("the console's pages: " + root + ": " + ec.message());
  std::size_t bytes = 0;
  for (fs::recursive_directory_iterator it(base, fs::directory_options::none, ec), end; !ec && it != end;
       it.increment(ec)) {
    if (!it->is_regular_file(ec) || it->is_symlink(ec)) continue;
    const std::string name = "/" + fs::relative(it->path(), base, ec).generic_string();
    if (files_.size() >= kMostFiles)
      throw std::runtime_error("the console's pages: more than " + std::to_string(kMostFiles) + " files in " +
                               root);
    std::string why;
    std::optional<std::string> content = io::read_bounded_file(it->path().string(), kMostBytes - bytes, why);
    if (!content) throw std::runtime_error("the console's pages: " + it->path().string() + ": " + why);
    bytes += content->size();
    files_[name] = {content_type(it->path()), std::move(*content)};
  }
  if (ec) throw std::runtime_error("the console's pages: " + root + ": " + ec.message());
}

const StaticFiles::File* StaticFiles::find(const std::string& path) const {
  const auto found = files_.find(path == "/" ? "/index.html" : path);
  return found == files_.end() ? nullptr : &found->second;
}

void Connections::make_room() {
  while (open >= most && evict_oldest()) {
  }
}

bool Connections::evict_oldest() {
  while (!waiting.empty()) {
    const std::shared_ptr<HttpSession> oldest = waiting.front().lock();
    waiting.pop_front();
    if (!oldest) continue;
    oldest->evict();
    return true;
  }
  return false;
}

bool Console::login_blocked(const std::string& key, Clock::time_point now) {
  std::deque<Clock::time_point>& failures = login_failures_[key];
  while (!failures.empty() && now - failures.front() > kLoginWindow)
    failures.pop_front();
  return static_cast<int>(failures.size()) >= kLoginFailuresAllowed;
}

std::optional<Console::Response> Console::login(Call& c) {
  const auto& request = c.request;
  const std::string& peer = c.peer;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const std::optional<std::string> name = text_field(*body, "name", 64, why);
  const std::optional<std::string> password =
      name ? text_field(*body, "password", 256, why, true, true) : std::nullopt;
  if (!name || !password) return error(request, http::status::bad_request, why);
  const Clock::time_point now = Clock::now();
  if (login_blocked("address " + peer, now) || login_blocked("account " + *name, now))
    return error(request, http::status::too_many_requests, "too many failed logins: wait a minute");
  const std::optional<records::AccountRow> row = db_.account(*name);
  // an unknown name costs a password check as a known one does
  const std::string& hash = row ? row->password_hash : unknown_account_hash_;
  const bool verified = crypto_pwhash_str_verify(hash.c_str(), password->data(), password->size()) == 0;
  if (!row || !verified) {
    login_failures_["address " + peer].push_back(now);
    login_failures_["account " + *name].push_back(now);
    audit_.add(*name, "login_failed", "", "from " + peer);
    return error(request, http::status::unauthorized, "wrong name or password");
  }
  const std::string token = random_token();
  LoginSession session{{row->name, row->role, row->trainee}, random_token(), now + kSessionLifetime};
  sessions_[token] = session;
  audit_.add(row->name, "login", "", "from " + peer);
  Response r = json_reply(
      request, http::status::ok,
      {{"name", row->name}, {"role", row->role}, {"trainee", row->trainee}, {"csrf", session.csrf}});
  r.set(http::field::set_cookie,
        "hs_session=" + token + "; Path=/; HttpOnly; SameSite=Strict; Max-Age=43200" + secure_cookie());
  return r;
}

std::string Console::stations_message() const {
  json list = json::array();
  for (const auto& [name, station] : link_.stations())
    list.push_back(status_json(name, station));
  return dump(json{{"type", "stations"}, {"stations", list}});
}

std::optional<Console::Response> Console::command(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  const std::string& station = c.segment;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const std::optional<std::string> kind = text_field(*body, "kind", 48, why);
  const std::optional<std::string> exercise =
      kind ? text_field(*body, "exercise", 128, why, false) : std::nullopt;
  const std::optional<std::string> trainee =
      exercise ? text_field(*body, "trainee", 64, why, false) : std::nullopt;
  const std::optional<std::string> route_id =
      trainee ? text_field(*body, "route", 64, why, false) : std::nullopt;
  const std::optional<std::string> team = route_id ? text_field(*body, "team", 64, why, false) : std::nullopt;
  const std::optional<std::string> role = team ? text_field(*body, "role", 32, why, false) : std::nullopt;
  if (!kind || !exercise || !trainee || !route_id || !team || !role)
    return error(request, http::status::bad_request, why);
  const auto autopilot = body->find("autopilot");
  if (autopilot != body->end() && !autopilot->is_boolean())
    return error(request, http::status::bad_request, "field 'autopilot' is not true or false");
  const auto found = link_.stations().find(station);
  if (found == link_.stations().end())
    return error(request, http::status::not_found, "no station '" + core::printable(station) + "'");
  if (found->second.lost || found->second.gone)
    return error(request, http::status::conflict, "station " + station + " is not on the network");
  std::string to_run = *exercise;
  if (*kind == "start" && !route_id->empty()) {
    // the trainee's next stage of the route, as the station will find it in the records
    const auto route =
        std::find_if(routes_.begin(), routes_.end(), [&](const auto& r) { return r.id == *route_id; });
    if (route == routes_.end())
      return error(request, http::status::not_found,
                   "field 'route': no route '" + core::printable(*route_id) + "'");
    if (trainee->empty() || !db_.has_trainee(*trainee))
      return error(request, http::status::bad_request,
                   "field 'trainee': a route's stage is run by a trainee in the records");
    const auto enrolled = db_.enrolments(*trainee);
    if (std::none_of(enrolled.begin(), enrolled.end(), [&](const auto& e) { return e.route == route->id; }))
      return error(request, http::status::conflict,
                   *trainee + " is not enrolled in route '" + route->id + "'");
    const training::RouteProgress p = training::progress(*route, db_.stage_attempts(*trainee, route->id),
                                                         db_.overrides(*trainee, route->id));
    if (!p.next)
      return error(request, http::status::conflict,
                   p.complete ? *trainee + " has passed every stage of " + route->id
                              : "no stage of " + route->id + " is open for " + *trainee +
                                    ": an instructor decides (sign off or retry)");
    to_run = route->stage(*p.next)->exercise;
  }
  if (*kind == "start" && !team->empty()) {
    // a member of a team session: the role's exercise, as the station will find it in the team file
    if (!exercise->empty() || !route_id->empty())
      return error(request, http::status::bad_request,
                   "a team's member runs its role's exercise: no exercise or route");
    const json teams = team_list(centre().exercise_folders());
    const auto found_team =
        std::find_if(teams.begin(), teams.end(), [&](const json& t) { return t["name"] == *team; });
    if (found_team == teams.end() || found_team->contains("error"))
      return error(request, http::status::not_found,
                   "field 'team': no team '" + core::printable(*team) + "'");
    std::string roles;
    for (const json& r : (*found_team)["roles"]) {
      roles += (roles.empty() ? "" : ", ") + r["role"].get<std::string>();
      if (r["role"] == *role) to_run = r["exercise"].get<std::string>();
    }
    if (to_run.empty())
      return error(request, http::status::bad_request,
                   "field 'role': team " + *team + " has no role '" + core::printable(*role) +
                       "' (its roles: " + roles + ")");
  }
  if (*kind == "start") {
    if (to_run.empty())
      return error(request, http::status::bad_request, "start needs an exercise or a route");
    if (!trainee->empty() && !db_.has_trainee(*trainee))
      return error(request, http::status::bad_request, "no trainee '" + core::printable(*trainee) + "'");
  }
  net::StationCommand sent;
  sent.station(station);
  sent.user(account.name);
  sent.kind(*kind);
  sent.exercise(to_run);
  sent.trainee(*trainee);
  sent.route(*kind == "start" ? *route_id : "");
  if (*kind == "start" && !team->empty()) {
    sent.exercise("");  // the station takes its role's exercise from the team file
    sent.team(*team);
    sent.role(*role);
  }
  sent.autopilot(autopilot != body->end() && autopilot->get<bool>());
  const std::uint64_t id = link_.send(sent);
  pending_[id] = Pending{request, c.session, account, station, *kind, Clock::now() + kAckTimeout};
  return std::nullopt;  // answered when the station acknowledges
}

// hold, resume or stop every running member of a team session at once
std::optional<Console::Response> Console::team_command(Call& c) {
  std::string why;
  const std::optional<json> body = parse_object(c.request.body(), why);
  if (!body) return error(c.request, http::status::bad_request, why);
  const std::optional<std::string> kind = text_field(*body, "kind", 48, why);
  if (!kind) return error(c.request, http::status::bad_request, why);
  if (*kind != "hold" && *kind != "resume" && *kind != "stop")
    return error(c.request, http::status::bad_request, "a team session takes hold, resume and stop");
  TeamPending p{c.request, c.session, *c.account, c.segment, *kind, {}, {}, Clock::now() + kAckTimeout};
  for (const auto& [name, station] : link_.stations()) {
    const std::string state = station.status.state().to_string();
    if (station.lost || station.gone || station.status.team().to_string() != c.segment ||
        (state != "running" && state != "held"))
      continue;
    net::StationCommand sent;
    sent.station(name);
    sent.user(c.account->name);
    sent.kind(*kind);
    p.sent.emplace_back(link_.send(sent), name);
  }
  if (p.sent.empty())
    return error(c.request, http::status::not_found,
                 "no station runs team '" + core::printable(c.segment) + "'");
  team_pending_.push_back(std::move(p));
  return std::nullopt;  // answered when every member has acknowledged
}

// ---------------------------------------------------------------------------------------------------
// The API's resources (Console::kRoutes says who may call each)

std::optional<Console::Response> Console::me(Call& c) {
  return json_reply(c.request, http::status::ok,
                    {{"name", c.account->name},
                     {"role", c.account->role},
                     {"trainee", c.account->trainee},
                     {"csrf", sessions_.at(c.token).csrf}});
}

std::optional<Console::Response> Console::logout(Call& c) {
  sessions_.erase(c.token);
  audit_.add(c.account->name, "logout", "", "");
  Response r = json_reply(c.request, http::status::ok, {{"ok", true}});
  r.set(http::field::set_cookie,
        "hs_session=; Path=/; HttpOnly; SameSite=Strict; Max-Age=0" + secure_cookie());
  return r;
}

std::optional<Console::Response> Console::stations(Call& c) {
  return json_reply(c.request, http::status::ok, json::parse(stations_message())["stations"]);
}

std::optional<Console::Response> Console::looks(Call& c) {
  Response r = json_reply(c.request, http::status::ok, json::object());
  r.body() = looks_;
  r.prepare_payload();
  return r;
}

std::optional<Console::Response> Console::exercises(Call& c) {
  json list = json::array();
  for (const io::ExerciseCard& card : io::exercise_cards(centre().exercise_folders())) {
    const sim::MachineType* type = sim::find_machine_type(card.machine);
    json item = {
        {"name", card.name}, {"machine", card.machine}, {"machine_title", type ? type->title : card.machine}};
    if (card.about)
      item.update({{"title", card.about->title},
                   {"objective", card.about->objective},
                   {"difficulty", card.about->difficulty},
                   {"expected_min", card.about->expected_min}});
    if (!card.error.empty() && c.account->instructs()) item["error"] = card.error;
    list.push_back(std::move(item));
  }
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::teams(Call& c) {
  return json_reply(c.request, http::status::ok, team_list(centre().exercise_folders()));
}

std::optional<Console::Response> Console::xapi_status(Call& c) {
  std::map<std::string, int> by_state = db_.xapi_counts();
  return json_reply(c.request, http::status::ok,
                    {{"lrs", options_.lrs},
                     {"queued", by_state["queued"]},
                     {"sent", by_state["sent"]},
                     {"rejected", by_state["rejected"]},
                     {"last", xapi_ ? xapi_->last_report() : ""}});
}

std::optional<Console::Response> Console::trainees(Call& c) {
  json list = json::array();
  for (const records::TraineeRow& t : db_.trainees())
    list.push_back({{"id", t.id}, {"name", t.name}});
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::change_trainee(Call& c) {
  const auto& request = c.request;
  const bool adds = request.method() == http::verb::post;  // a new trainee; PATCH renames one
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  const std::optional<std::string> id = body ? text_field(*body, "id", 64, why) : std::nullopt;
  const std::optional<std::string> name = id ? text_field(*body, "name", 128, why) : std::nullopt;
  if (!name) return error(request, http::status::bad_request, why);
  try {
    if (adds)
      db_.add_trainee(*id, *name);
    else
      db_.rename_trainee(*id, *name);
  } catch (const std::out_of_range& e) {
    return error(request, http::status::not_found, e.what());
  } catch (const std::exception& e) {
    return error(request, http::status::bad_request, e.what());
  }
  audit_.add(c.account->name, adds ? "add_trainee" : "rename_trainee", *id, *name);
  return json_reply(request, adds ? http::status::created : http::status::ok, {{"id", *id}, {"name", *name}});
}

std::optional<Console::Response> Console::attempts(Call& c) {
  std::optional<std::string> trainee;
  if (!c.trainee.empty()) trainee = c.trainee;
  json list = json::array();
  for (const records::AttemptRow& a : db_.attempts(trainee))
    list.push_back({{"id", a.id},
                    {"trainee", a.trainee},
                    {"exercise", a.exercise},
                    {"status", a.status},
                    {"outcome", records::attempt_outcome(a)},
                    {"score", a.score ? json(*a.score) : json(nullptr)},
                    {"passed", a.passed},
                    {"moves", a.moves},
                    {"parent", a.parent ? json(*a.parent) : json(nullptr)},
                    {"route", a.route},
                    {"stage", a.stage},
                    {"exercise_version", a.exercise_version},
                    {"started_at", a.started_at},
                    {"ended_at", a.ended_at},
                    {"autopilot", a.autopilot},
                    {"team", a.team},
                    {"team_role", a.team_role},
                    {"team_session", a.team_session}});
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::attempt(Call& c) {
  const auto& request = c.request;
  const std::int64_t id = c.segment_id;
  const std::optional<records::AttemptRow> a = db_.attempt(id);
  if (!a || !owns(*c.account, a->trainee))
    return error(request, http::status::not_found, "no attempt " + std::to_string(id) + " for you");
  json events = json::array(), metrics = json::object(), figures = json::array(), deductions = json::array();
  for (const records::DeductionRow& d : db_.deductions(id))
    deductions.push_back(
        {{"reason", d.reason}, {"skill", d.skill}, {"count", d.count}, {"points", d.points}});
  for (const records::EventRow& e : db_.events(id))
    events.push_back(attempt_event_json(e.at_s, e.kind, e.value));
  std::vector<std::pair<std::string, double>> stored;
  for (const auto& [name, value] : db_.metrics(id)) {
    metrics[name] = value;
    stored.emplace_back(name, value);
  }
  // the figures in words, in the figure table's order
  std::stable_sort(stored.begin(), stored.end(), [](const auto& x, const auto& y) {
    return training::figure_order(x.first) < training::figure_order(y.first);
  });
  for (const auto& [name, value] : stored) {
    const training::FigureWords words = training::figure_words(name);
    figures.push_back({{"name", name},
                       {"label", words.label},
                       {"text", training::figure_text(words, value)},
                       {"about", words.about}});
  }
  json detail = {{"id", a->id},
                 {"trainee", a->trainee},
                 {"exercise", a->exercise},
                 {"status", a->status},
                 {"outcome", records::attempt_outcome(*a)},
                 {"score", a->score ? json(*a->score) : json(nullptr)},
                 {"passed", a->passed},
                 {"events", events},
                 {"metrics", metrics},
                 {"figures", figures},
                 {"deductions", deductions}};
  if (c.account->instructs()) detail["recording"] = a->recording;  // where its station wrote it
  return json_reply(request, http::status::ok, detail);
}

std::optional<Console::Response> Console::attempts_csv_file(Call& c) {
  if (!c.trainee.empty() && !db_.has_trainee(c.trainee))
    return error(c.request, http::status::not_found, "no trainee '" + core::printable(c.trainee) + "'");
  Response r = json_reply(c.request, http::status::ok, json::object());
  r.set(http::field::content_type, "text/csv; charset=utf-8");
  r.set(http::field::content_disposition, "attachment; filename=\"attempts.csv\"");
  r.body() = attempts_csv(c.trainee.empty() ? std::nullopt : std::optional(c.trainee));
  r.prepare_payload();
  return r;
}

std::optional<Console::Response> Console::trainee_evolution(Call& c) {
  if (c.trainee.empty()) return error(c.request, http::status::bad_request, "evolution of whom: ?trainee=ID");
  if (!db_.has_trainee(c.trainee))
    return error(c.request, http::status::not_found, "no trainee '" + core::printable(c.trainee) + "'");
  return json_reply(c.request, http::status::ok, evolution(c.trainee));
}

std::optional<Console::Response> Console::routes(Call& c) {
  json list = json::array();
  for (const training::Route& r : routes_)
    list.push_back(route_json(r));
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::progress(Call& c) {
  const auto& request = c.request;
  const std::string& trainee = c.trainee;
  if (trainee.empty()) return error(request, http::status::bad_request, "progress of whom: ?trainee=ID");
  if (!db_.has_trainee(trainee))
    return error(request, http::status::not_found, "no trainee '" + core::printable(trainee) + "'");
  json list = json::array();
  for (const records::EnrolmentRow& e : db_.enrolments(trainee)) {
    const auto route =
        std::find_if(routes_.begin(), routes_.end(), [&](const auto& r) { return r.id == e.route; });
    if (route == routes_.end()) continue;  // a route of another centre's folder
    const std::vector<training::Override> decided = db_.overrides(trainee, route->id);
    const training::RouteProgress p =
        training::progress(*route, db_.stage_attempts(trainee, route->id), decided);
    json stages = json::array();
    for (const training::StageProgress& sp : p.stages)
      stages.push_back({{"stage", sp.stage},
                        {"state", training::state_name(sp.state)},
                        {"attempts", sp.attempts},
                        {"attempts_allowed", sp.attempts_allowed},
                        {"passes", sp.passes},
                        {"best_score", sp.best_score ? json(*sp.best_score) : json(nullptr)},
                        {"signed_off", sp.signed_off},
                        {"missing", sp.missing}});
    json decisions = json::array();
    for (const training::Override& o : decided)
      decisions.push_back({{"stage", o.stage},
                           {"action", o.action},
                           {"reason", o.reason},
                           {"account", o.account},
                           {"at", o.at}});
    list.push_back({{"route", e.route},
                    {"enrolled_at", e.at},
                    {"next", p.next ? json(*p.next) : json(nullptr)},
                    {"complete", p.complete},
                    {"stages", stages},
                    {"decisions", decisions}});
  }
  return json_reply(request, http::status::ok, {{"trainee", trainee}, {"routes", list}});
}

std::optional<Console::Response> Console::enrol_or_decide(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  const std::optional<std::string> trainee = body ? text_field(*body, "trainee", 64, why) : std::nullopt;
  const std::optional<std::string> route_id = trainee ? text_field(*body, "route", 64, why) : std::nullopt;
  if (!route_id) return error(request, http::status::bad_request, why);
  const auto route =
      std::find_if(routes_.begin(), routes_.end(), [&](const auto& r) { return r.id == *route_id; });
  if (route == routes_.end())
    return error(request, http::status::not_found,
                 "field 'route': no route '" + core::printable(*route_id) + "'");
  if (!db_.has_trainee(*trainee))
    return error(request, http::status::not_found,
                 "field 'trainee': no trainee '" + core::printable(*trainee) + "'");
  if (c.target == "/api/enrolments") {
    const bool added = db_.enrol(*trainee, route->id, account.name);
    if (added) audit_.add(account.name, "enrol", *trainee, route->id);
    return json_reply(request, added ? http::status::created : http::status::ok,
                      {{"trainee", *trainee}, {"route", route->id}, {"enrolled", true}});
  }
  const std::optional<std::string> stage = text_field(*body, "stage", 64, why);
  const std::optional<std::string> action = stage ? text_field(*body, "action", 16, why) : std::nullopt;
  const std::optional<std::string> reason = action ? text_field(*body, "reason", 500, why) : std::nullopt;
  if (!reason) return error(request, http::status::bad_request, why);
  if (!route->stage(*stage))
    return error(request, http::status::bad_request,
                 "field 'stage': route '" + route->id + "' has no stage '" + core::printable(*stage) + "'");
  if (*action != "sign_off" && *action != "retry")
    return error(request, http::status::bad_request, "field 'action': sign_off or retry");
  try {
    db_.add_override(*trainee, route->id, {*stage, *action, *reason, account.name, ""});
  } catch (const std::out_of_range& e) {
    return error(request, http::status::conflict, e.what());
  } catch (const std::invalid_argument& e) {
    return error(request, http::status::bad_request, e.what());
  }
  audit_.add(account.name, *action, *trainee + " " + route->id + "/" + *stage, *reason);
  return json_reply(request, http::status::created,
                    {{"trainee", *trainee}, {"route", route->id}, {"stage", *stage}, {"action", *action}});
}

std::optional<Console::Response> Console::audit_log(Call& c) {
  json list = json::array();
  audit_.flush();  // the log as it stands, the entries just queued in it
  for (const records::AuditRow& a : db_.audit_log(200))
    list.push_back({{"at", a.at},
                    {"account", a.account},
                    {"action", a.action},
                    {"target", a.target},
                    {"detail", a.detail}});
  return json_reply(c.request, http::status::ok, list);
}

std::optional<Console::Response> Console::add_account(Call& c) {
  const auto& request = c.request;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  const std::optional<std::string> name = body ? text_field(*body, "name", 64, why) : std::nullopt;
  const std::optional<std::string> password =
      name ? text_field(*body, "password", 256, why, true, true) : std::nullopt;
  const std::optional<std::string> role = password ? text_field(*body, "role", 16, why) : std::nullopt;
  const std::optional<std::string> trainee =
      role ? text_field(*body, "trainee", 64, why, false) : std::nullopt;
  if (!trainee) return error(request, http::status::bad_request, why);
  if (password->size() < 8)
    return error(request, http::status::bad_request, "a password of 8 characters or more");
  try {
    db_.add_account({*name, *role, hash_password(*password), *trainee});
  } catch (const std::invalid_argument& e) {
    return error(request, http::status::bad_request, e.what());
  }
  audit_.add(c.account->name, "add_account", *name, *role);
  return json_reply(request, http::status::created, {{"name", *name}, {"role", *role}});
}

std::optional<Console::Response> Console::design_source(Call& c) {
  const std::string name = query_param(c.query, "exercise");
  for (const std::string& folder : centre().exercise_folders()) {
    try {
      const std::string text = console::design_source(folder, name);
      return json_reply(c.request, http::status::ok,
                        {{"exercise", name}, {"text", text}, {"designed", designed(text)}});
    } catch (const std::out_of_range&) {
    }
  }
  return error(c.request, http::status::not_found, "no exercise '" + core::printable(name) + "'");
}

std::optional<Console::Response> Console::check_or_save_design(Call& c) {
  std::string why;
  const std::optional<json> body = parse_object(c.request.body(), why);
  const auto text = body ? body->find("text") : json::const_iterator{};
  if (!body || text == body->end() || !text->is_string())
    return error(c.request, http::status::bad_request, body ? "field 'text': the exercise's YAML" : why);
  const bool save = c.target == "/api/designer/save";
  // the loader and the preview's world run beside the console's thread: a slow or hostile design holds up
  // nobody else
  beside(c, checks_, kMostChecksAtOnce, kCheckBudget,
         [this, save, folder = exercise_folder(), yaml = text->get<std::string>(), request = c.request,
          account = c.account->name]() -> Finish {
           DesignCheck design;
           try {
             design = check_design(folder, yaml);
           } catch (const std::invalid_argument& e) {
             return [this, request, why = std::string(e.what())] {
               return error(request, http::status::unprocessable_entity, why);
             };
           }
           if (save)
             return [this, request, account, design] {
               std::string file;
               try {
                 file = save_design(exercise_folder(), design);
               } catch (const std::logic_error& e) {
                 return error(request, http::status::conflict, e.what());
               }
               audit_.add(account, "save_exercise", design.exercise.name, design.version);
               return json_reply(
                   request, http::status::created,
                   {{"exercise", design.exercise.name}, {"version", design.version}, {"file", file}});
             };
           json preview;
           try {
             preview = design_preview(folder, design);
           } catch (const std::exception& e) {
             return [this, request, why = std::string(e.what())] {
               return error(request, http::status::unprocessable_entity,
                            "the design loads but its world cannot be built: " + why);
             };
           }
           return [this, request, preview = std::move(preview)] {
             return json_reply(request, http::status::ok, preview);
           };
         });
  return std::nullopt;
}

std::optional<Console::Response> Console::route_text(Call& c) {
  const std::string id = query_param(c.query, "route");
  try {
    const std::string text = route_source(centre(), id);
    return json_reply(c.request, http::status::ok,
                      {{"route", id}, {"text", text}, {"designed", designed(text)}});
  } catch (const std::out_of_range& e) {
    return error(c.request, http::status::not_found, e.what());
  }
}

std::optional<Console::Response> Console::check_or_save_route(Call& c) {
  const auto& request = c.request;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const auto id = body->find("id"), text = body->find("text");
  if (id == body->end() || !id->is_string())
    return error(request, http::status::bad_request, "field 'id': the route's file name");
  if (text == body->end() || !text->is_string())
    return error(request, http::status::bad_request, "field 'text': the route's YAML");
  const bool save = c.target == "/api/routes/save";
  beside(c, checks_, kMostChecksAtOnce, kCheckBudget,
         [this, save, folders = centre(), id = id->get<std::string>(), yaml = text->get<std::string>(),
          request, account = c.account->name]() -> Finish {
           RouteCheck route;
           try {
             route = check_route_text(folders, id, yaml);
           } catch (const std::invalid_argument& e) {
             return [this, request, why = std::string(e.what())] {
               return error(request, http::status::unprocessable_entity, why);
             };
           }
           json stages = route_json(route.route);
           for (std::size_t n = 0; n < route.route.stages.size(); ++n)
             stages["stages"][n]["exercise_version"] =
                 io::exercise_version(route.route.stages[n].exercise_file);
           return [this, save, request, account, route, stages = std::move(stages)]() mutable {
             // people pick a route by its title: another route's is refused (the console's routes: its
             // thread)
             for (const training::Route& other : routes_)
               if (other.id != route.route.id && other.name == route.route.name)
                 return error(request, http::status::unprocessable_entity,
                              "route.name: '" + route.route.name + "' is also the name of route '" +
                                  other.id + "': give this route a name of its own");
             if (!save) return json_reply(request, http::status::ok, stages);
             return save_route_now(request, account, route, std::move(stages));
           };
         });
  return std::nullopt;
}

Console::Response Console::save_route_now(const http::request<http::string_body>& request,
                                          const std::string& account, const RouteCheck& route, json stages) {
  const std::string file_name = route.route.id + ".yaml";
  std::string file, before;
  try {
    before = route_source(centre(), route.route.id);
  } catch (const std::out_of_range&) {
  }
  try {
    file = save_route(centre(), route);
  } catch (const std::logic_error& e) {
    return error(request, http::status::conflict, e.what());
  }
  // the console's routes with it; should another file of the folder spoil them, the save is undone
  try {
    routes_ = records::load_centre_routes(centre());
  } catch (const std::exception& e) {
    std::error_code ec;
    if (before.empty())
      std::filesystem::remove(file, ec);
    else
      std::ofstream(file, std::ios::binary) << before;
    return error(request, http::status::unprocessable_entity,
                 std::string("saved, the centre's routes no longer load, so it was undone: ") + e.what());
  }
  audit_.add(account, "save_route", route.route.id, file_name);
  stages["file"] = file;
  return json_reply(request, http::status::created, stages);
}

std::optional<Console::Response> Console::open_replay(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  if (!body) return error(request, http::status::bad_request, why);
  const auto attempt = body->find("attempt");
  if (attempt == body->end() || !attempt->is_number_integer() || attempt->get<std::int64_t>() <= 0)
    return error(request, http::status::bad_request, "field 'attempt': an attempt id");
  const std::int64_t id = attempt->get<std::int64_t>();
  const std::optional<records::AttemptRow> row = db_.attempt(id);
  if (!row) return error(request, http::status::not_found, "no attempt " + std::to_string(id));
  if (row->recording.empty())
    return error(request, http::status::conflict, "attempt " + std::to_string(id) + " was not recorded");
  if (static_cast<int>(replays_.size()) >= Replay::kMostOpen)
    return error(request, http::status::too_many_requests,
                 "already " + std::to_string(Replay::kMostOpen) + " replays open: close one");
  Replay replay;
  std::string version, inexact;  // of the exercise replayed: the version the attempt ran, kept in the records
  try {
    const io::ExerciseSource source = records::attempt_exercise(db_, *row, exercise_folder(), inexact);
    replay.exercise = io::load_exercise_source(source);
    version = source.version;
    replay.recording = db_.read_recording_of(*row);  // the station may be another PC
  } catch (const std::exception& e) {
    return error(request, http::status::conflict, std::string("cannot replay: ") + e.what());
  }
  replay.id = next_replay_++;
  replay.attempt = id;
  replay.recording_file = row->recording;
  replay.trainee = row->trainee;
  replay.owner = account.name;
  auto [it, added] = replays_.emplace(replay.id, std::move(replay));
  Replay& r = it->second;
  try {
    r.player = std::make_unique<sim::ReplayPlayer>(r.exercise.scenario, r.recording);
  } catch (const std::exception& e) {
    replays_.erase(it);
    return error(request, http::status::conflict, std::string("cannot replay: ") + e.what());
  }
  r.scene = net::scene_message(r.player->simulation().scene(), r.attempt);
  json events = json::array();
  for (const records::EventRow& e : db_.events(id))
    events.push_back(attempt_event_json(e.at_s, e.kind, e.value));
  for (const sim::Recording::Command& given : r.recording.commands)
    events.push_back(attempt_event_json(static_cast<double>(given.step) * sim::Simulation::kStep_s,
                                        std::string("instructor ") + io::command_name(given.command.kind),
                                        0.0));
  std::sort(events.begin(), events.end(),
            [](const json& a, const json& b) { return a["at_s"].get<double>() < b["at_s"].get<double>(); });
  audit_.add(account.name, "open_replay", "attempt " + std::to_string(id), r.recording_file);
  return json_reply(request, http::status::created,
                    {{"replay", r.id},
                     {"station", "replay-" + std::to_string(r.id)},
                     {"attempt", id},
                     {"exercise", r.exercise.name},
                     {"exercise_version", version},
                     {"trainee", r.trainee},
                     {"duration_s", static_cast<double>(r.recording.total_steps) * sim::Simulation::kStep_s},
                     {"complete", r.recording.complete},
                     {"exact", inexact.empty()},
                     {"note", inexact},
                     {"events", events}});
}

std::optional<Console::Response> Console::control_replay(Call& c) {
  const auto& request = c.request;
  const Account& account = *c.account;
  const std::int64_t id = c.segment_id;
  const std::shared_ptr<HttpSession>& session = c.session;
  const auto found = replays_.find(id);
  if (found == replays_.end())
    return error(request, http::status::not_found, "no replay " + std::to_string(id));
  Replay& r = found->second;
  std::string why;
  const std::optional<json> body = parse_object(request.body(), why);
  const std::optional<std::string> action = body ? text_field(*body, "action", 16, why) : std::nullopt;
  if (!action) return error(request, http::status::bad_request, why);
  const auto number = [&](const char* field, double low, double high) -> std::optional<double> {
    const auto f = body->find(field);
    if (f == body->end() || !f->is_number() || !(f->get<double>() >= low && f->get<double>() <= high)) {
      why = std::string("field '") + field + "': a number from " + std::to_string(low) + " to " +
            std::to_string(high);
      return std::nullopt;
    }
    return f->get<double>();
  };
  const double duration_s = static_cast<double>(r.recording.total_steps) * sim::Simulation::kStep_s;
  if (*action == "play" || *action == "pause") {
    r.playing = *action == "play";
    if (body->contains("speed")) {
      const std::optional<double> speed = number("speed", 0.25, 8.0);
      if (!speed) return error(request, http::status::bad_request, why);
      r.speed = *speed;
    }
    r.last_poll = Clock::now();
  } else if (*action == "seek") {
    const std::optional<double> at = number("at_s", 0.0, duration_s);
    if (!at) return error(request, http::status::bad_request, why);
    try {
      r.player->seek(static_cast<std::int64_t>(std::llround(*at / sim::Simulation::kStep_s)));
    } catch (const std::exception& e) {
      return error(request, http::status::conflict, std::string("cannot seek: ") + e.what());
    }
    r.position_steps = static_cast<double>(r.player->simulation().steps());
    r.bulk = {};  // the material as it was then: copied whole again (tile versions restart with the state)
  } else if (*action == "take-over") {
    // the attempt continues live at a station from the moment shown, as a new attempt of a trainee
    const std::optional<std::string> station = text_field(*body, "station", 64, why);
    const std::optional<std::string> trainee =
        station ? text_field(*body, "trainee", 64, why, false) : std::nullopt;
    if (!trainee) return error(request, http::status::bad_request, why);
    const auto found_station = link_.stations().find(*station);
    if (found_station == link_.stations().end() || found_station->second.lost || found_station->second.gone)
      return error(request, http::status::not_found,
                   "no station '" + core::printable(*station) + "' on the network");
    if (!trainee->empty() && !db_.has_trainee(*trainee))
      return error(request, http::status::bad_request, "no trainee '" + core::printable(*trainee) + "'");
    const auto autopilot = body->find("autopilot");
    r.playing = false;
    net::StationCommand sent;
    sent.station(*station);
    sent.user(account.name);
    sent.kind("take-over");
    sent.exercise(r.exercise.name);
    sent.trainee(trainee->empty() ? r.trainee : *trainee);
    sent.autopilot(autopilot != body->end() && autopilot->is_boolean() && autopilot->get<bool>());
    sent.recording(r.recording_file);
    sent.step(r.player->simulation().steps());
    const std::uint64_t command = link_.send(sent);
    pending_[command] = Pending{request,
                                session,
                                account,
                                *station,
                                "take-over of attempt " + std::to_string(r.attempt) + " at step " +
                                    std::to_string(r.player->simulation().steps()),
                                Clock::now() + kAckTimeout};
    return std::nullopt;
  } else if (*action == "close") {
    audit_.add(account.name, "close_replay", "attempt " + std::to_string(r.attempt), "");
    replays_.erase(found);
    return json_reply(request, http::status::ok, {{"closed", id}});
  } else {
    return error(request, http::status::bad_request, "action: play, pause, seek, take-over or close");
  }
  json state = replay_state(r);
  state["playing"] = r.playing;
  state["speed"] = r.speed;
  return json_reply(request, http::status::ok, state);
}

json Console::replay_state(Replay& r, bool view) {
  const sim::Simulation& sim = r.player->simulation();
  sim.write_snapshot(*r.snapshot);
  json state =
      state_json("replay-" + std::to_string(r.id),
                 net::state_message(*r.snapshot, sim.scene().entities.size(), r.attempt), &r.scene, view);
  state["held"] = !r.playing;
  state["replay"] = r.id;
  state["checkpoint_mismatch"] = r.player->first_mismatch().has_value();
  return state;
}

void Console::push_state(LiveSocket& socket, const std::string& station, const net::StationScene* scene,
                         const std::function<json(bool)>& state_of) {
  if (socket.wants_view() && scene) {
    const std::string key = station + " " + std::to_string(scene->attempt());
    if (socket.scene_sent() != key) {
      socket.send(dump(scene_json(station, *scene)));
      socket.scene_sent() = key;
    }
  }
  socket.send(dump(state_of(socket.wants_view())));
}

void Console::play_replays(Clock::time_point now) {
  for (auto& [id, r] : replays_) {
    const double dt = std::chrono::duration<double>(now - r.last_poll).count();
    r.last_poll = now;
    if (!r.playing) continue;
    r.position_steps =
        std::min(r.position_steps + dt * r.speed / sim::Simulation::kStep_s,
                 static_cast<double>(r.player->simulation().steps() + Replay::kMostStepsPerPoll));
    try {
      r.player->advance_to(static_cast<std::int64_t>(r.position_steps));
    } catch (const std::exception&) {
      r.playing = false;  // a damaged recording: it stops where it could go no further
    }
    if (r.player->simulation().steps() >= r.player->total_steps()) r.playing = false;
  }
}

const Console::Route* Console::route_of(Call& call, http::verb method) {
  for (const Route& route : kRoutes) {
    if (route.method != method) continue;
    // the path, '*' and '#' each standing for one non-empty segment
    const std::string_view pattern = route.path, target = call.target;
    std::size_t p = 0, t = 0;
    std::string segment;
    bool match = true;
    while (match && p < pattern.size() && t <= target.size()) {
      if (pattern[p] == '*' || pattern[p] == '#') {
        const std::size_t end = std::min(target.find('/', t), target.size());
        segment = std::string(target.substr(t, end - t));
        match = !segment.empty();
        t = end;
        ++p;
      } else {
        match = t < target.size() && pattern[p] == target[t];
        ++p;
        ++t;
      }
    }
    if (!match || p != pattern.size() || t != target.size()) continue;
    call.segment = segment;
    return &route;
  }
  return nullptr;
}

std::string Console::refusal(Who who, Call& call) {
  const Account& account = *call.account;
  switch (who) {
    case Who::kAnyone:
    case Who::kAnyAccount:
      return "";
    case Who::kOwnRecords: {
      const std::string asked = query_param(call.query, "trainee");
      if (account.instructs()) {
        call.trainee = asked;
        return "";
      }
      if (!asked.empty() && asked != account.trainee) return "a trainee sees only their own records";
      call.trainee = account.trainee;
      return "";
    }
    case Who::kStaff:
      return account.instructs() ? "" : "not for a " + account.role;
    case Who::kAdministrators:
      return account.role == "administrator" ? "" : "not for a " + account.role;
  }
  return "not allowed";
}

std::string Console::foreign_origin(const http::request<http::string_body>& request) const {
  const auto origin = request.find(http::field::origin);
  if (origin == request.end()) return "";  // not a browser's request from a page (a browser always says)
  const auto lower = [](beast::string_view text) {
    std::string out(text);
    for (char& ch : out)
      ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return out;
  };
  const std::string from = lower(origin->value());
  const auto host = request.find(http::field::host);
  if (host != request.end() &&
      from == (options_.tls_certificate.empty() ? "http://" : "https://") + lower(host->value()))
    return "";
  for (const std::string& allowed : options_.allowed_origins)
    if (from == lower(allowed)) return "";
  return "a request from the page of another origin (" + core::printable(std::string(origin->value()), 100) +
         "): refused";
}

std::string Console::refuse_live(const http::request<http::string_body>& request, http::status& status,
                                 std::string& token) {
  status = http::status::not_found;
  if (request.target() != "/api/live") return "the live socket is /api/live";
  status = http::status::forbidden;
  if (std::string why = foreign_origin(request); !why.empty()) return why;
  token = token_of(request);
  status = http::status::unauthorized;
  Call call{request, "/api/live", "", "", nullptr, token, account_of(token)};
  if (!call.account) return "log in first (the live socket is /api/live)";
  status = http::status::forbidden;
  if (std::string why = refusal(kLiveSocket, call); !why.empty())
    return why + ": the live socket is for staff";
  status = http::status::service_unavailable;
  if (sockets_.size() >= kMostLiveSockets)
    return "already " + std::to_string(kMostLiveSockets) + " live sockets open";
  return "";
}

std::string Console::refuse_subscription(const std::string& token, const std::string& station) {
  const http::request<http::string_body> none;
  Call call{none, "/api/live", "", "", nullptr, token, account_of(token)};
  if (!call.account) return "logged out";
  if (std::string why = refusal(kLiveSocket, call); !why.empty()) return why;
  (void)station;  // staff watch every station and every replay
  return "";
}

void Console::handle(const http::request<http::string_body>& request, const std::string& peer,
                     std::shared_ptr<HttpSession> session) {
  const std::string target(request.target().substr(0, request.target().find('?')));
  try {
    if (target.rfind("/api/", 0) != 0) {
      if (request.method() != http::verb::get && request.method() != http::verb::head)
        return session->reply(error(request, http::status::method_not_allowed, "pages are read only"));
      return session->reply(file(request));
    }
    const bool changes = request.method() != http::verb::get && request.method() != http::verb::head;
    if (changes) {
      // a state-changing request must come from our own pages: JSON, and (a browser's) same origin
      const auto type = request.find(http::field::content_type);
      if (type == request.end() || std::string(type->value()).rfind("application/json", 0) != 0)
        return session->reply(error(request, http::status::unsupported_media_type, "send application/json"));
      if (const std::string why = foreign_origin(request); !why.empty())
        return session->reply(error(request, http::status::forbidden, why));
    }
    const auto question = request.target().find('?');
    Call call{request, target,
              question == std::string::npos ? "" : std::string(request.target().substr(question + 1)), peer,
              session};
    const Route* route = route_of(call, request.method());
    if (!route || route->who != Who::kAnyone) {
      call.token = token_of(request);
      call.account = account_of(call.token);
      if (!call.account) return session->reply(error(request, http::status::unauthorized, "log in first"));
    }
    if (!route)
      return session->reply(
          error(request, http::status::not_found, "no such API: " + core::printable(target)));
    if (route->who != Who::kAnyone) {
      if (changes) {
        const auto csrf = request.find("X-CSRF-Token");
        if (csrf == request.end() || std::string(csrf->value()) != sessions_.at(call.token).csrf)
          return session->reply(error(request, http::status::forbidden, "missing or wrong X-CSRF-Token"));
      }
      if (const std::string why = refusal(route->who, call); !why.empty())
        return session->reply(error(request, http::status::forbidden, why));
    }
    if (route->path.find('#') != std::string_view::npos) {
      std::size_t used = 0;
      try {
        call.segment_id = std::stoll(call.segment, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != call.segment.size() || call.segment_id <= 0 || call.segment.size() > 15)
        return session->reply(error(request, http::status::bad_request, "id: a positive number"));
    }
    if (std::optional<Response> r = (this->*route->handler)(call)) session->reply(std::move(*r));
  } catch (const std::exception& e) {
    session->reply(error(request, http::status::internal_server_error, e.what()));
  }
}

void Console::poll() {
  const Clock::time_point now = Clock::now();
  const std::vector<std::string> changed = link_.poll(now);
  std::erase_if(sockets_, [](const std::shared_ptr<LiveSocket>& s) { return !s->open(); });
  // sockets of sessions logged out or expired are closed
  for (const auto& s : sockets_)
    if (!account_of(s->token())) s->close("logged out");
  std::erase_if(sockets_, [](const std::shared_ptr<LiveSocket>& s) { return !s->open(); });
  // the stations' table at most 5 times a second, whatever the number of stations
  stations_changed_ = stations_changed_ || !changed.empty();
  if (stations_changed_ && now >= next_stations_push_) {
    const std::string message = stations_message();
    for (const auto& s : sockets_)
      s->send(message);
    stations_changed_ = false;
    next_stations_push_ = now + std::chrono::milliseconds(200);
  }
  for (const net::StationEvent& e : link_.take_events()) {
    const std::string message = dump(event_json(e));
    for (const auto& s : sockets_)
      s->send(message);
  }
  play_replays(now);
  if (now >= next_state_push_) {
    next_state_push_ = now + std::chrono::milliseconds(100);
    for (const auto& s : sockets_) {
      if (s->subscribed().rfind("replay-", 0) == 0) {
        for (auto& [id, r] : replays_)
          if (s->subscribed() == "replay-" + std::to_string(id))
            push_state(*s, s->subscribed(), &r.scene, [&](bool view) { return replay_state(r, view); });
        for (auto& [id, r] : replays_)
          if (s->subscribed() == "replay-" + std::to_string(id) && s->wants_view())
            if (const bulk::BulkWorld* material = r.player->simulation().bulk()) {
              // each second of the replay's time (and after a seek)
              const std::string key =
                  s->subscribed() + " " + std::to_string(std::lround(r.player->simulation().time_s()));
              if (s->bulk_sent() != key) {
                bulk::publish(*material, r.bulk);
                s->send(dump(bulk_json(
                    s->subscribed(), net::bulk_message(r.bulk, r.attempt, r.player->simulation().time_s()))));
                s->bulk_sent() = key;
              }
            }
        continue;
      }
      const auto found = link_.stations().find(s->subscribed());
      if (s->subscribed().empty() || found == link_.stations().end() || !found->second.state) continue;
      const net::StationState& st = *found->second.state;
      const net::StationScene* scene = found->second.scene ? &*found->second.scene : nullptr;
      push_state(*s, s->subscribed(), scene,
                 [&](bool view) { return state_json(s->subscribed(), st, scene, view); });
      if (s->wants_view() && found->second.bulk) {
        const std::string key = s->subscribed() + " " + std::to_string(found->second.bulk_count);
        if (s->bulk_sent() != key) {
          s->send(dump(bulk_json(s->subscribed(), *found->second.bulk)));
          s->bulk_sent() = key;
        }
      }
      // what the trainee sees, as the station draws it (a JPEG picture a few times a second)
      if (found->second.picture) {
        const std::string key = s->subscribed() + " " + std::to_string(found->second.picture_count);
        if (s->picture_sent() != key) {
          const net::StationPicture& p = *found->second.picture;
          const std::vector<std::uint8_t>& jpeg = p.jpeg();
          s->send(dump(json{{"type", "picture"},
                            {"station", s->subscribed()},
                            {"attempt", p.attempt()},
                            {"time_s", p.time_s()},
                            {"width", p.width()},
                            {"height", p.height()},
                            {"jpeg", records::to_base64(std::string_view(
                                         reinterpret_cast<const char*>(jpeg.data()), jpeg.size()))}}));
          s->picture_sent() = key;
        }
      }
    }
  }
  // each station a browser shows is told so every 2 s (it draws its trainee's pictures only then); the
  // acknowledgements of these are dropped
  if (now >= next_watch_) {
    next_watch_ = now + std::chrono::seconds(2);
    std::set<std::string> shown;
    for (const auto& s : sockets_)
      if (!s->subscribed().empty() && s->subscribed().rfind("replay-", 0) != 0) shown.insert(s->subscribed());
    for (const std::string& station : shown) {
      const auto found = link_.stations().find(station);
      if (found == link_.stations().end() || found->second.lost || found->second.gone) continue;
      net::StationCommand watch;
      watch.station(station);
      watch.user(options_.name);
      watch.kind("watch");
      watches_.push_back({link_.send(watch), now + kAckTimeout});
    }
  }
  std::erase_if(watches_, [&](const std::pair<std::uint64_t, Clock::time_point>& w) {
    return link_.take_ack(w.first).has_value() || now > w.second;
  });
  for (auto it = pending_.begin(); it != pending_.end();) {
    Pending& p = it->second;
    const std::optional<net::CommandAck> ack = link_.take_ack(it->first);
    if (!ack && now < p.deadline) {
      ++it;
      continue;
    }
    const std::string outcome = !ack        ? "no answer"
                                : ack->ok() ? "done"
                                            : "refused: " + ack->message().to_string();
    audit_.add(p.account.name, "command " + p.kind, p.station, outcome);
    if (!ack)
      p.session->reply(error(p.request, http::status::gateway_timeout,
                             "station " + p.station + " did not answer within 3 s"));
    else
      p.session->reply(json_reply(p.request, ack->ok() ? http::status::ok : http::status::conflict,
                                  {{"ok", ack->ok()}, {"message", ack->message().to_string()}}));
    it = pending_.erase(it);
  }
  for (auto it = team_pending_.begin(); it != team_pending_.end();) {
    TeamPending& p = *it;
    for (const auto& [id, station] : p.sent)
      if (!p.answers.count(station))
        if (const std::optional<net::CommandAck> ack = link_.take_ack(id)) p.answers[station] = *ack;
    if (p.answers.size() < p.sent.size() && now < p.deadline) {
      ++it;
      continue;
    }
    json stations = json::array();
    bool all_ok = true;
    for (const auto& [id, station] : p.sent) {
      const auto answer = p.answers.find(station);
      const bool ok = answer != p.answers.end() && answer->second.ok();
      const std::string message =
          answer == p.answers.end() ? "no answer within 3 s" : answer->second.message().to_string();
      all_ok = all_ok && ok;
      stations.push_back({{"station", station}, {"ok", ok}, {"message", message}});
      audit_.add(p.account.name, "command " + p.kind, station,
                 "team " + p.team + ": " + (ok ? "done" : message));
    }
    p.session->reply(json_reply(p.request, all_ok ? http::status::ok : http::status::conflict,
                                {{"ok", all_ok}, {"team", p.team}, {"stations", stations}}));
    it = team_pending_.erase(it);
  }
  if (g_stop) {
    io_.stop();
    return;
  }
  poll_timer_.expires_after(std::chrono::milliseconds(2));
  poll_timer_.async_wait([this](beast::error_code ec) {
    if (!ec) poll();
  });
}

json Console::evolution(const std::string& trainee) {
  const std::vector<training::AttemptFigures> all = db_.attempt_figures();
  json attempts = json::array();
  json words = {{"score", figure_words_json("score")}};  // each figure's label and unit, for the plots
  for (const training::AttemptFigures& a : all) {
    if (a.trainee != trainee || a.status != "finished" || !a.score) continue;
    json skills = json::object(), metrics = json::object();
    for (const auto& [name, value] : a.metrics) {
      metrics[name] = value;
      if (name.rfind("skill_", 0) == 0) skills[name.substr(6)] = value;
      if (!words.contains(name)) words[name] = figure_words_json(name);
    }
    attempts.push_back({{"id", a.id},
                        {"exercise", a.exercise},
                        {"exercise_version", a.exercise_version},
                        {"route", a.route},
                        {"stage", a.stage},
                        {"score", *a.score},
                        {"passed", a.passed},
                        {"skills", skills},
                        {"metrics", metrics}});
  }
  json cohort = json::array(), standings = json::array();
  for (const training::Standing& s : training::standings(all, trainee)) {
    json line = {{"exercise", s.exercise},
                 {"exercise_version", s.exercise_version},
                 {"figure", s.figure},
                 {"label", training::figure_words(s.figure).label},
                 {"higher_better", s.higher_better},
                 {"best", s.best},
                 {"best_text", training::figure_text(s.figure, s.best)},
                 {"trainees", s.trainees},
                 {"percentile", s.percentile},
                 {"place", s.place},
                 {"tied", s.tied},
                 {"place_words", training::place_words(s.place, s.trainees, s.tied)}};
    if (s.figure == "score") cohort.push_back(line);
    standings.push_back(std::move(line));
  }
  json routes = json::array();
  for (const training::RouteStanding& r : records::route_standings(db_, routes_, trainee)) {
    int passed = 0;
    for (const training::StageProgress& p : r.progress.stages)
      passed += p.state == training::StageState::kPassed ? 1 : 0;
    routes.push_back({{"route", r.route.id},
                      {"name", r.route.name},
                      {"stages", r.progress.stages.size()},
                      {"passed", passed},
                      {"next", r.progress.next ? json(*r.progress.next) : json(nullptr)},
                      {"complete", r.progress.complete}});
  }
  return {{"trainee", trainee}, {"figures", words},       {"attempts", attempts},
          {"cohort", cohort},   {"standings", standings}, {"routes", routes}};
}

std::optional<Console::Response> Console::class_overview(Call& c) {
  const auto optional_number = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
  const training::ClassReportData d = records::class_report_data(db_, routes_);
  json lines = json::array();
  for (std::size_t i = 0; i < d.lines.size(); ++i) {
    const training::TraineeSummary& t = d.lines[i];
    json routes = json::array();
    for (const training::RouteStanding& r : d.routes[i]) {
      int passed = 0;
      for (const training::StageProgress& p : r.progress.stages)
        passed += p.state == training::StageState::kPassed ? 1 : 0;
      routes.push_back({{"route", r.route.id},
                        {"stages", r.progress.stages.size()},
                        {"passed", passed},
                        {"next", r.progress.next ? json(*r.progress.next) : json(nullptr)},
                        {"complete", r.progress.complete}});
    }
    lines.push_back({{"trainee", t.trainee},
                     {"name", d.names[i]},
                     {"attempts", t.attempts},
                     {"finished", t.finished},
                     {"passed", t.passed},
                     {"first_score", optional_number(t.first_score)},
                     {"last_score", optional_number(t.last_score)},
                     {"best_score", optional_number(t.best_score)},
                     {"recent_score", optional_number(t.recent_score)},
                     {"recent_skills",
                      {{"safety", optional_number(t.recent_skills[0])},
                       {"precision", optional_number(t.recent_skills[1])},
                       {"productivity", optional_number(t.recent_skills[2])}}},
                     {"trend", optional_number(t.trend)},
                     {"routes", routes}});
  }
  return json_reply(c.request, http::status::ok, lines);
}

std::optional<Console::Response> Console::compare(Call& c) {
  const auto optional_number = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
  const std::string first = query_param(c.query, "a"), second = query_param(c.query, "b");
  if (first.empty() || second.empty())
    return error(c.request, http::status::bad_request, "compare whom: ?a=ID&b=ID");
  for (const std::string& id : {first, second})
    if (!db_.has_trainee(id))
      return error(c.request, http::status::not_found, "no trainee '" + core::printable(id) + "'");
  json figures = json::array();
  for (const training::Compared& x : training::compare(db_.attempt_figures(), first, second))
    figures.push_back({{"exercise", x.exercise},
                       {"exercise_version", x.exercise_version},
                       {"figure", x.figure},
                       {"label", training::figure_words(x.figure).label},
                       {"higher_better", x.higher_better},
                       {"a", optional_number(x.first)},
                       {"b", optional_number(x.second)},
                       {"a_text", x.first ? training::figure_text(x.figure, *x.first) : ""},
                       {"b_text", x.second ? training::figure_text(x.figure, *x.second) : ""}});
  return json_reply(c.request, http::status::ok, {{"a", first}, {"b", second}, {"figures", figures}});
}

// reports: /api/reports/trainee?trainee=ID, /api/reports/class, each also as .pdf
std::optional<Console::Response> Console::report(Call& c) {
  const auto& request = c.request;
  const bool pdf = c.target.size() > 4 && c.target.compare(c.target.size() - 4, 4, ".pdf") == 0;
  const std::string page = pdf ? c.target.substr(0, c.target.size() - 4) : c.target;
  std::string html, name;
  if (page == "/api/reports/trainee") {
    if (c.trainee.empty()) return error(request, http::status::bad_request, "a report on whom: ?trainee=ID");
    if (!db_.has_trainee(c.trainee))
      return error(request, http::status::not_found, "no trainee '" + core::printable(c.trainee) + "'");
    html = training::trainee_report_html(records::trainee_report_data(db_, routes_, c.trainee));
    name = "trainee-" + c.trainee;
  } else {
    html = training::class_report_html(records::class_report_data(db_, routes_));
    name = "class";
  }
  // a file name a browser may save under: letters, digits, - and _ only
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '_';
  if (!pdf) {
    Response r = json_reply(request, http::status::ok, json::object());
    r.set(http::field::content_type, "text/html; charset=utf-8");
    r.body() = std::move(html);
    r.prepare_payload();
    return r;
  }
  audit_.add(c.account->name, "report", name, "pdf");
  // chromium prints beside the console's thread
  beside(c, printing_, kMostPrintsAtOnce, kPrintBudget,
         [this, request, html = std::move(html), name]() -> Finish {
           char folder[] = "/tmp/harboursim-pdf-XXXXXX";
           if (!mkdtemp(folder))
             return [this, request] {
               return error(request, http::status::internal_server_error, "cannot make a temporary folder");
             };
           const std::filesystem::path file = std::filesystem::path(folder) / "report.pdf";
           std::string bytes, why;
           try {
             records::print_pdf(html, file);
             std::ifstream in(file, std::ios::binary);
             bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
           } catch (const std::exception& e) {
             why = e.what();
           }
           std::error_code ignored;
           std::filesystem::remove_all(folder, ignored);
           return [this, request, bytes = std::move(bytes), why, name] {
             if (!why.empty()) return error(request, http::status::internal_server_error, why);
             Response r = json_reply(request, http::status::ok, json::object());
             r.set(http::field::content_type, "application/pdf");
             r.set(http::field::content_disposition, "attachment; filename=\"" + name + ".pdf\"");
             r.body() = bytes;
             r.prepare_payload();
             return r;
           };
         });
  return std::nullopt;
}

void Console::beside(Call& c, int& running, int most, std::chrono::seconds budget,
                     std::function<Finish()> work) {
  if (running >= most) {
    c.session->reply(
        error(c.request, http::status::service_unavailable,
              "the console is busy with " + std::to_string(running) + " such requests; try again shortly"));
    return;
  }
  ++running;
  struct Waiting {
    bool answered = false;
    asio::steady_timer timer;
    explicit Waiting(asio::io_context& io) : timer(io) {}
  };
  auto waiting = std::make_shared<Waiting>(io_);
  // past its budget the request is answered now; the work's late answer is dropped
  waiting->timer.expires_after(budget);
  waiting->timer.async_wait(
      [this, waiting, session = c.session, request = c.request, budget](beast::error_code ec) {
        if (ec || waiting->answered) return;
        waiting->answered = true;
        session->reply(error(request, http::status::service_unavailable,
                             "not done within " + std::to_string(budget.count()) + " s: refused"));
      });
  std::thread worker([this, waiting, &running, session = c.session, request = c.request,
                      work = std::move(work)] {
    Finish finish;
    try {
      finish = work();
    } catch (const std::exception& e) {
      finish = [this, request, why = std::string(e.what())] {
        return error(request, http::status::internal_server_error, why);
      };
    }
    asio::post(
        io_, [this, waiting, &running, session, finish = std::move(finish), id = std::this_thread::get_id()] {
          --running;
          if (auto done = workers_.extract(id)) done.mapped().join();  // it has nothing left to do
          waiting->timer.cancel();
          if (waiting->answered) return;
          waiting->answered = true;
          session->reply(finish());
        });
  });
  workers_.emplace(worker.get_id(), std::move(worker));
}

std::string Console::attempts_csv(const std::optional<std::string>& trainee) {
  const auto cell = [](const std::string& text) {
    std::string out = "\"";
    if (!text.empty() && std::string("=+-@\t\r").find(text[0]) != std::string::npos) out += '\'';
    for (char c : text)
      out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  // a UTF-8 byte-order mark first: spreadsheet programs otherwise read the names in the local code page
  std::string csv =
      "\xEF\xBB\xBF"
      "id,trainee,exercise,exercise_version,route,stage,status,score,passed,moves,skill_safety,skill_"
      "precision,"
      "skill_productivity\r\n";
  std::vector<records::AttemptRow> rows = db_.attempts(trainee);
  std::reverse(rows.begin(), rows.end());
  for (const records::AttemptRow& a : rows) {
    std::map<std::string, double> skills;
    for (const auto& [name, value] : db_.metrics(a.id))
      skills[name] = value;
    const auto figure = [](std::optional<double> v) {
      if (!v) return std::string();
      char text[32];
      std::snprintf(text, sizeof text, "%.6g", *v);
      return std::string(text);
    };
    const auto skill = [&](const char* name) {
      const auto found = skills.find(name);
      return figure(found == skills.end() ? std::nullopt : std::optional(found->second));
    };
    csv += std::to_string(a.id) + "," + cell(a.trainee) + "," + cell(a.exercise) + "," +
           cell(a.exercise_version) + "," + cell(a.route) + "," + cell(a.stage) + "," + cell(a.status) + "," +
           figure(a.score) + "," + (a.passed ? "1" : "0") + "," + std::to_string(a.moves) + "," +
           skill("skill_safety") + "," + skill("skill_precision") + "," + skill("skill_productivity") +
           "\r\n";
  }
  return csv;
}

void accept(tcp::acceptor& acceptor, Console& console, asio::ssl::context* tls, asio::steady_timer& retry) {
  acceptor.async_accept([&acceptor, &console, tls, &retry](beast::error_code ec, tcp::socket socket) {
    if (ec == asio::error::no_descriptors || ec.value() == ENFILE || ec == asio::error::no_buffer_space) {
      // out of file descriptors: close the connection idle the longest and try again shortly (not at once:
      // that would spin)
      console.connections()->evict_oldest();
      retry.expires_after(std::chrono::milliseconds(20));
      retry.async_wait(
          [&acceptor, &console, tls, &retry](beast::error_code) { accept(acceptor, console, tls, retry); });
      return;
    }
    if (!ec) console.connections()->make_room();
    if (!ec && tls)
      std::make_shared<HttpConnection<TlsStream>>(TlsStream(std::move(socket), *tls), console)->start();
    else if (!ec)
      std::make_shared<HttpConnection<beast::tcp_stream>>(beast::tcp_stream(std::move(socket)), console)
          ->start();
    if (ec == asio::error::operation_aborted) return;  // the console is ending
    accept(acceptor, console, tls, retry);
  });
}

// As many open files as the system lets this process have (the soft limit raised to the hard one); returns
// the limit.
std::size_t raise_file_limit() {
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0) return 1024;
  if (limit.rlim_cur < limit.rlim_max) {
    limit.rlim_cur = limit.rlim_max;
    setrlimit(RLIMIT_NOFILE, &limit);
    getrlimit(RLIMIT_NOFILE, &limit);
  }
  return limit.rlim_cur == RLIM_INFINITY ? std::size_t{1} << 20 : static_cast<std::size_t>(limit.rlim_cur);
}

// The server's TLS context from PEM files (TLS 1.2 and later); an error names the file.
std::unique_ptr<asio::ssl::context> tls_context(const ConsoleOptions& options) {
  if (options.tls_certificate.empty() != options.tls_key.empty())
    throw std::runtime_error("TLS needs both --tls-cert and --tls-key");
  if (options.tls_certificate.empty()) return nullptr;
  auto context = std::make_unique<asio::ssl::context>(asio::ssl::context::tls_server);
  context->set_options(asio::ssl::context::default_workarounds | asio::ssl::context::no_sslv2 |
                       asio::ssl::context::no_sslv3 | asio::ssl::context::no_tlsv1 |
                       asio::ssl::context::no_tlsv1_1 | asio::ssl::context::single_dh_use);
  boost::system::error_code ec;
  context->use_certificate_chain_file(options.tls_certificate, ec);
  if (ec)
    throw std::runtime_error("--tls-cert " + options.tls_certificate +
                             ": not a readable PEM certificate chain (" + ec.message() + ")");
  context->use_private_key_file(options.tls_key, asio::ssl::context::pem, ec);
  const bool mismatch =
      ec && ERR_GET_REASON(static_cast<unsigned long>(ec.value())) == X509_R_KEY_VALUES_MISMATCH;
  if (mismatch || (!ec && SSL_CTX_check_private_key(context->native_handle()) != 1))
    throw std::runtime_error("--tls-key " + options.tls_key + ": not the key of --tls-cert " +
                             options.tls_certificate);
  if (ec)
    throw std::runtime_error("--tls-key " + options.tls_key + ": not a readable PEM private key (" +
                             ec.message() + ")");
  return context;
}

}  // namespace

int run_console(const ConsoleOptions& given) {
  if (sodium_init() < 0) throw std::runtime_error("libsodium could not start");
  ConsoleOptions options = given;
  if (options.name.empty()) options.name = "console-" + std::to_string(getpid());
  if (options.database.empty()) options.database = records::default_database();
  if (options.web_root.empty()) options.web_root = std::string(HARBOUR_WEB_DIR);
  boost::system::error_code ec;
  const asio::ip::address address = asio::ip::make_address(options.bind, ec);
  if (ec) throw std::runtime_error("--bind " + options.bind + ": not an IP address");
  const std::unique_ptr<asio::ssl::context> tls = tls_context(options);
  if (!address.is_loopback() && !tls)
    throw std::runtime_error("--bind " + options.bind +
                             ": a console on the centre's network serves TLS only: give its certificate "
                             "and key with --tls-cert and --tls-key (PEM files)");
  if (!std::filesystem::is_regular_file(std::filesystem::path(options.web_root) / "index.html"))
    throw std::runtime_error("the console's pages are not built: " + options.web_root +
                             "/index.html is missing (./harbour build builds them)");
  asio::io_context io;
  Console console(options, io);
  const std::size_t files = raise_file_limit();
  console.connections()->most = files > 2 * kReservedFiles ? files - kReservedFiles : files / 2;
  tcp::acceptor acceptor(io);
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(options.port));
  acceptor.open(endpoint.protocol());
  acceptor.set_option(asio::socket_base::reuse_address(true));
  acceptor.bind(endpoint, ec);
  if (ec)
    throw std::runtime_error("console: cannot listen on " + options.bind + ":" +
                             std::to_string(options.port) + ": " + ec.message());
  acceptor.listen();
  g_stop = 0;
  std::signal(SIGINT, on_console_signal);
  std::signal(SIGTERM, on_console_signal);
  std::signal(SIGPIPE, SIG_IGN);
  if (console.accounts() == 0)
    std::printf(
        "no accounts yet: add the first administrator with\n  harboursim accounts add admin --role "
        "administrator%s\n(its password on standard input)\n",
        given.database.empty() ? "" : (" --db " + given.database).c_str());
  std::printf("console %s: %s://%s:%u/ (DDS domain %d, records %s)\n", options.name.c_str(),
              tls ? "https" : "http", options.bind.c_str(),
              static_cast<unsigned>(acceptor.local_endpoint().port()), options.domain,
              options.database.c_str());
  std::fflush(stdout);
  asio::steady_timer retry(io);
  accept(acceptor, console, tls.get(), retry);
  console.start_polling();
  if (options.seconds > 0.0)
    io.run_for(std::chrono::milliseconds(static_cast<std::int64_t>(options.seconds * 1e3)));
  else
    io.run();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  return 0;
}

int list_accounts(const std::string& database) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  for (const records::AccountRow& a : db.accounts())
    std::printf("%-24s %s\n", core::printable(a.name).c_str(), a.role.c_str());
  return 0;
}

int add_account(const std::string& database, const std::string& name, const std::string& role,
                const std::string& trainee) {
  if (sodium_init() < 0) throw std::runtime_error("libsodium could not start");
  std::string password;
  if (!std::getline(std::cin, password)) throw std::runtime_error("no password on standard input");
  if (password.size() < 8 || password.size() > 256)
    throw std::runtime_error("the password: 8 to 256 characters");
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  db.add_account({name, role, hash_password(password), trainee});
  db.audit("(command line)", "add_account", name, role);
  std::printf("account %s (%s) added\n", name.c_str(), role.c_str());
  return 0;
}

}  // namespace harbour::console
