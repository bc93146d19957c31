#include "XapiCommand.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <map>
#include <thread>

#include "harbour/records/Centre.h"
#include "harbour/records/XapiSender.h"

namespace harbour::apps {
namespace {

volatile std::sig_atomic_t g_stop = 0;
extern "C" void stop_watching(int) {
  g_stop = 1;
}

}  // namespace

int xapi_status(const std::string& database) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  std::map<std::string, int> by_state = db.xapi_counts();
  const std::vector<records::XapiRow> rows = db.xapi_outbox();
  std::printf("xAPI outbox: %d queued, %d sent, %d rejected\n", by_state["queued"], by_state["sent"],
              by_state["rejected"]);
  for (const records::XapiRow& r : rows)
    if (!r.last_error.empty())
      std::printf("  %s %s (attempt %lld, %d tries, %s): %s\n", r.state.c_str(), r.verb.c_str(),
                  static_cast<long long>(r.attempt), r.tries,
                  r.state == "queued" ? ("next at " + r.next_try_at).c_str() : "not retried",
                  r.last_error.c_str());
  return 0;
}

int xapi_send(const std::string& database, const std::string& endpoint, const std::string& credentials_file,
              bool watch, const training::xapi::Centre& centre) {
  records::RecordsStore db(database.empty() ? records::default_database() : database);
  const records::LrsOptions lrs{endpoint, records::read_lrs_credentials(credentials_file), centre};
  records::check_lrs_endpoint(endpoint);  // a bad URL stops it before anything is tried
  g_stop = 0;
  if (watch) {
    std::signal(SIGINT, stop_watching);
    std::signal(SIGTERM, stop_watching);
  }
  int waiting = 0;
  do {
    const records::SendReport r = records::send_due(db, lrs);
    if (r.sent || r.retry || r.rejected) {
      std::printf("xapi: %d sent, %d to retry, %d rejected%s%s\n", r.sent, r.retry, r.rejected,
                  r.last_error.empty() ? "" : "; ", r.last_error.c_str());
      std::fflush(stdout);
    }
    waiting = r.retry;
    if (watch)
      for (int n = 0; n < 10 && !g_stop; ++n)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } while (watch && !g_stop);
  if (watch) {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  }
  return waiting ? 3 : 0;
}

}  // namespace harbour::apps
