#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

#include "harbour/records/RecordsStore.h"

namespace harbour::records {

/// The console's audit log, written off the server's thread: an instructor's command is answered without
/// waiting for the records database (another process — a station storing its attempt — may hold its write
/// lock, and SQLite's busy wait sleeps up to 100 ms at a time). Each entry is stamped when it happens and
/// written, in order, by a thread of its own with its own connection; a failed write is tried again every
/// second, and whatever is queued is written before the writer is destroyed.
class AuditWriter {
 public:
  explicit AuditWriter(std::string database);
  ~AuditWriter();
  AuditWriter(const AuditWriter&) = delete;
  AuditWriter& operator=(const AuditWriter&) = delete;

  /// Queues an entry stamped now (never blocks on the database).
  void add(const std::string& account, const std::string& action, const std::string& target,
           const std::string& detail);
  /// Waits until every entry queued so far is written (or `timeout_s` has passed: false).
  bool flush(double timeout_s = 10.0);
  /// The last write's failure ("" : none since).
  std::string last_error() const;

 private:
  void run();
  std::string database_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, written_;
  std::deque<AuditRow> queue_;
  std::uint64_t queued_ = 0, done_ = 0;  // entries ever queued and ever written
  bool stop_ = false;
  std::string last_error_;
  std::thread thread_;
};

}  // namespace harbour::records
