// The instructor console's server: static files, the JSON API and the live WebSocket, over Boost.Beast
// (the WebSocket and TLS streams in this one translation unit: Beast is slow to compile). One thread runs
// everything: the HTTP and WebSocket sessions, the records database and the DDS link, polled every few
// milliseconds. The resources' handlers are in a file each (ConsoleServer.h).
#include "harbour/console/ConsoleServer.h"

#include <sodium.h>
#include <sys/resource.h>
#include <unistd.h>

#include <openssl/err.h>
#include <openssl/x509.h>
#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/core/Text.h"
#include "harbour/io/BoundedFile.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/io/InstructorCommandText.h"
#include "harbour/io/RecordingFile.h"
#include "harbour/io/RouteFiles.h"
#include "harbour/io/TeamFiles.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/records/Reports.h"
#include "harbour/sim/MachineType.h"
#include "harbour/training/Figures.h"

namespace harbour::console {

namespace websocket = beast::websocket;

namespace {

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_console_signal(int) {
  g_stop = 1;
}

}  // namespace

using tcp = asio::ip::tcp;

constexpr std::size_t kMaxBodyBytes = 64 * 1024;     // the API's requests are small
constexpr std::size_t kMaxSocketMessage = 4 * 1024;  // a browser's WebSocket messages are smaller still
// a connection's request (or the TLS handshake) must arrive within this: an idle keep-alive connection closes
constexpr auto kRequestTimeout = std::chrono::seconds(30);

// file descriptors kept free of HTTP connections (the records database, the DDS link, live sockets, threads)
constexpr std::size_t kReservedFiles = 1024;

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

// Every API route and who may call it: read this table to know what each role can see and do.
const Console::Route Console::kRoutes[] = {
    {http::verb::post, "/api/login", Who::kAnyone, &Console::login},
    {http::verb::get, "/api/me", Who::kAnyAccount, &Console::me},
    {http::verb::post, "/api/logout", Who::kAnyAccount, &Console::logout},
    {http::verb::get, "/api/looks", Who::kAnyAccount, &Console::looks},
    {http::verb::get, "/api/exercises", Who::kAnyAccount, &Console::exercises},
    {http::verb::get, "/api/commands", Who::kSignallers, &Console::commands},
    {http::verb::get, "/api/teams", Who::kStaff, &Console::teams},
    {http::verb::post, "/api/teams/*/command", Who::kStaff, &Console::team_command},
    {http::verb::post, "/api/teams/*/start", Who::kStaff, &Console::team_start},
    {http::verb::get, "/api/routes", Who::kAnyAccount, &Console::routes},
    {http::verb::get, "/api/attempts", Who::kOwnRecords, &Console::attempts},
    {http::verb::get, "/api/attempts/#", Who::kOwnRecords, &Console::attempt},
    {http::verb::get, "/api/attempts.csv", Who::kOwnRecords, &Console::attempts_csv_file},
    {http::verb::get, "/api/evolution", Who::kOwnRecords, &Console::trainee_evolution},
    {http::verb::get, "/api/progress", Who::kOwnRecords, &Console::progress},
    {http::verb::get, "/api/reports/trainee", Who::kOwnRecords, &Console::report},
    {http::verb::get, "/api/reports/trainee.pdf", Who::kOwnRecords, &Console::report},
    {http::verb::get, "/api/stations", Who::kSignallers, &Console::stations},
    {http::verb::post, "/api/stations/*/command", Who::kSignallers, &Console::command},
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
      if (account.trainee.empty()) return "not for a " + account.role;  // no records of its own (a signaller)
      if (!asked.empty() && asked != account.trainee) return "a trainee sees only their own records";
      call.trainee = account.trainee;
      return "";
    }
    case Who::kStaff:
      return account.instructs() ? "" : "not for a " + account.role;
    case Who::kSignallers:
      return account.instructs() || account.signals() ? "" : "not for a " + account.role;
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
            push_state(*s, s->subscribed(), &r.scene, r.player->names_version(),
                       [&](bool view) { return replay_state(r, view); });
        for (auto& [id, r] : replays_)
          if (s->subscribed() == "replay-" + std::to_string(id) && s->wants_view())
            if (const bulk::BulkWorld* material = r.player->player(0).simulation().bulk()) {
              // each second of the replay's time (and after a seek)
              const std::string key = s->subscribed() + " " + std::to_string(std::lround(r.player->time_s()));
              if (s->bulk_sent() != key) {
                bulk::publish(*material, r.bulk);
                s->send(dump(
                    bulk_json(s->subscribed(), net::bulk_message(r.bulk, r.attempt, r.player->time_s()))));
                s->bulk_sent() = key;
              }
            }
        continue;
      }
      const auto found = link_.stations().find(s->subscribed());
      if (s->subscribed().empty() || found == link_.stations().end() || !found->second.state) continue;
      const net::StationState& st = *found->second.state;
      const net::StationScene* scene = found->second.scene ? &*found->second.scene : nullptr;
      push_state(*s, s->subscribed(), scene, found->second.scene_count,
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

}  // namespace harbour::console
