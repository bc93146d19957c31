#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "harbour/records/Centre.h"
#include "harbour/records/RecordsStore.h"
#include "harbour/training/Xapi.h"

namespace harbour::records {

/// A Learning Record Store: its xAPI endpoint (http:// or https://, e.g. "http://lrs.centre:8080/xAPI/") and
/// the HTTP Basic credentials "user:password" ("" : none).
struct LrsOptions {
  std::string endpoint;
  std::string credentials;
  training::xapi::Centre centre;  ///< whose statements they are, as they leave (training::xapi::addressed)
  double timeout_s = 10.0;
};

/// The centre the statements leave from: its IRI ("" : http://HOSTNAME/harboursim, this machine's name) and
/// its exercises' titles and objectives from its folders.
training::xapi::Centre xapi_centre(const std::string& iri, const CentreFolders& folders);

/// What one pass over the outbox did.
struct SendReport {
  int sent = 0;
  int retry = 0;     ///< failed, queued for a later try (the LRS down, busy, or refusing the credentials)
  int rejected = 0;  ///< refused for good (an invalid statement, or another statement under its id)
  std::string last_error;
};

/// Sends the queued statements of the outbox in order up to the first whose next try has not come, each by
/// PUT statements?statementId=ID (xAPI 1.0.3: the LRS keeps one statement per id, so a statement sent twice,
/// its answer lost, is stored once). 200/204 mark it sent; 400, 409 and 413 reject it; anything else, or no
/// answer, queues it again after 2 s x 2^tries (at most 5 min) and ends the pass (the LRS is not asked again
/// until then).
SendReport send_due(RecordsStore& db, const LrsOptions& lrs, int most = 200);

/// Throws std::invalid_argument naming what is wrong with an LRS endpoint (http:// or https://, a host).
void check_lrs_endpoint(const std::string& endpoint);

/// The credentials in an LRS credentials file: one line user:password; throws naming the file.
std::string read_lrs_credentials(const std::string& file);

/// The console's sender: send_due every second on a thread of its own, with its own connection to the
/// records, until destroyed.
class XapiWorker {
 public:
  XapiWorker(std::string database, LrsOptions lrs);
  ~XapiWorker();
  XapiWorker(const XapiWorker&) = delete;
  XapiWorker& operator=(const XapiWorker&) = delete;
  /// What the last pass that did something said ("" : none yet).
  std::string last_report() const;

 private:
  void run();
  std::string database_;
  LrsOptions lrs_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::string last_;
  std::thread thread_;
};

}  // namespace harbour::records
