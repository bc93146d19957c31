#include "harbour/records/XapiSender.h"

#include <utility>  // before Boost.Asio 1.74, which uses std::exchange without it

#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast.hpp>
#include <boost/beast/ssl.hpp>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <thread>

#include <unistd.h>

#include "harbour/core/Text.h"
#include "harbour/io/ExerciseFiles.h"

namespace harbour::records {

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

struct Endpoint {
  bool tls = false;
  std::string host, port, path;  // path ends with '/'
};

Endpoint parse_endpoint(const std::string& url) {
  Endpoint e;
  std::string rest;
  if (url.rfind("http://", 0) == 0) {
    rest = url.substr(7);
  } else if (url.rfind("https://", 0) == 0) {
    e.tls = true;
    rest = url.substr(8);
  } else {
    throw std::invalid_argument("--lrs '" + core::printable(url) + "': an http:// or https:// URL");
  }
  const auto slash = rest.find('/');
  const std::string authority = rest.substr(0, slash);
  e.path = slash == std::string::npos ? "/" : rest.substr(slash);
  if (e.path.back() != '/') e.path += '/';
  const auto colon = authority.rfind(':');
  e.host = authority.substr(0, colon);
  e.port = colon == std::string::npos ? (e.tls ? "443" : "80") : authority.substr(colon + 1);
  if (e.host.empty() || e.port.empty() || e.port.find_first_not_of("0123456789") != std::string::npos ||
      authority.find('@') != std::string::npos)
    throw std::invalid_argument("--lrs '" + core::printable(url) +
                                "': http(s)://HOST[:PORT]/PATH/ (credentials go in --lrs-auth-file)");
  return e;
}

// UTC ISO 8601 with milliseconds, `seconds` from now: the outbox's times compare as text
std::string utc_after(double seconds) {
  return records::utc_time(
      std::chrono::system_clock::now() + std::chrono::duration_cast<std::chrono::system_clock::duration>(
                                             std::chrono::duration<double>(seconds)),
      3);
}

// one PUT; the HTTP status, or throws (no answer) saying why
template <class Stream>
http::response<http::string_body> round_trip(Stream& stream,
                                             const http::request<http::string_body>& request) {
  http::write(stream, request);
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(1 << 20);
  http::read(stream, buffer, parser);
  return parser.release();
}

http::response<http::string_body> put_statement(const Endpoint& e, const LrsOptions& lrs,
                                                const XapiRow& row) {
  http::request<http::string_body> request{http::verb::put,
                                           e.path + "statements?statementId=" + row.statement_id, 11};
  // RFC 9112 (3.2): Host is the URI's host and its port, which may only be left out where it is the scheme's
  // default (a virtual host behind the port would otherwise not be found)
  const bool default_port = e.port == (e.tls ? "443" : "80");
  request.set(http::field::host, default_port ? e.host : e.host + ":" + e.port);
  request.set(http::field::content_type, "application/json");
  request.set("X-Experience-API-Version", "1.0.3");
  if (!lrs.credentials.empty())
    request.set(http::field::authorization, "Basic " + records::to_base64(lrs.credentials));
  request.body() = training::xapi::addressed(row.statement, lrs.centre);
  request.prepare_payload();
  asio::io_context io;
  tcp::resolver resolver(io);
  const auto addresses = resolver.resolve(e.host, e.port);
  const auto timeout = std::chrono::milliseconds(static_cast<long>(lrs.timeout_s * 1000.0));
  if (!e.tls) {
    beast::tcp_stream stream(io);
    stream.expires_after(timeout);
    stream.connect(addresses);
    return round_trip(stream, request);
  }
  asio::ssl::context context(asio::ssl::context::tls_client);
  context.set_default_verify_paths();
  context.set_verify_mode(asio::ssl::verify_peer);
  beast::ssl_stream<beast::tcp_stream> stream(io, context);
  if (!SSL_set_tlsext_host_name(stream.native_handle(), e.host.c_str()))
    throw std::runtime_error("TLS: cannot name the host");
  stream.set_verify_callback(asio::ssl::host_name_verification(e.host));
  beast::get_lowest_layer(stream).expires_after(timeout);
  beast::get_lowest_layer(stream).connect(addresses);
  stream.handshake(asio::ssl::stream_base::client);
  return round_trip(stream, request);
}

}  // namespace

void check_lrs_endpoint(const std::string& endpoint) {
  parse_endpoint(endpoint);
}

std::string read_lrs_credentials(const std::string& file) {
  if (file.empty()) return "";
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line))
    throw std::runtime_error("--lrs-auth-file " + file + ": cannot read it (one line: user:password)");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.find(':') == std::string::npos)
    throw std::runtime_error("--lrs-auth-file " + file + ": one line user:password");
  return line;
}

SendReport send_due(RecordsStore& db, const LrsOptions& lrs, int most) {
  const Endpoint e = parse_endpoint(lrs.endpoint);
  SendReport report;
  const std::string now = utc_after(0.0);
  for (const XapiRow& row : db.xapi_due("9999", most)) {  // every queued one, in order
    if (row.next_try_at > now) break;  // a failed one waits: those after it wait too, so that order holds
    const double wait_s = std::min(300.0, 2.0 * static_cast<double>(1 << std::min(row.tries, 8)));
    try {
      const auto answer = put_statement(e, lrs, row);
      const int status = answer.result_int();
      if (status == 200 || status == 204) {
        db.xapi_sent(row.id, utc_after(0.0));
        ++report.sent;
        continue;
      }
      report.last_error =
          "LRS answered " + std::to_string(status) + ": " + core::printable(answer.body(), 500);
      if (status == 400 || status == 409 || status == 413) {
        db.xapi_failed(row.id, report.last_error, row.next_try_at, true);
        ++report.rejected;
        continue;
      }
    } catch (const std::exception& ex) {
      report.last_error = std::string("no answer from the LRS: ") + ex.what();
    }
    db.xapi_failed(row.id, report.last_error, utc_after(wait_s), false);
    ++report.retry;
    break;  // down or refusing: not asked again before the next try
  }
  return report;
}

XapiWorker::XapiWorker(std::string database, LrsOptions lrs)
    : database_(std::move(database)), lrs_(std::move(lrs)) {
  parse_endpoint(lrs_.endpoint);  // a bad URL stops the console before it starts
  thread_ = std::thread([this] { run(); });
}

XapiWorker::~XapiWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::string XapiWorker::last_report() const {
  std::lock_guard lock(mutex_);
  return last_;
}

void XapiWorker::run() {
  std::unique_ptr<records::RecordsStore> db;
  std::unique_lock lock(mutex_);
  while (!stop_) {
    lock.unlock();
    std::string said;
    try {
      if (!db) db = std::make_unique<records::RecordsStore>(database_);
      const SendReport r = send_due(*db, lrs_);
      if (r.sent || r.retry || r.rejected)
        said = std::to_string(r.sent) + " sent, " + std::to_string(r.retry) + " to retry, " +
               std::to_string(r.rejected) + " rejected" + (r.last_error.empty() ? "" : "; " + r.last_error);
    } catch (const std::exception& e) {
      said = std::string("the records: ") + e.what();
      db.reset();  // opened again on the next pass
    }
    lock.lock();
    if (!said.empty()) last_ = utc_after(0.0) + ": " + said;
    wake_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; });
  }
}

training::xapi::Centre xapi_centre(const std::string& iri, const CentreFolders& folders) {
  training::xapi::Centre centre;
  centre.iri = iri;
  if (centre.iri.empty()) {
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    centre.iri = std::string("http://") + (host[0] ? host : "localhost") + "/harboursim";
  }
  while (!centre.iri.empty() && centre.iri.back() == '/')
    centre.iri.pop_back();
  for (const io::ExerciseCard& card : io::exercise_cards(folders.exercise_folders()))
    if (card.about) centre.exercises[card.name] = {card.about->title, card.about->objective};
  return centre;
}

}  // namespace harbour::records
