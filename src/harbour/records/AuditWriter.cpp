#include "harbour/records/AuditWriter.h"

#include <chrono>
#include <memory>
#include <utility>

namespace harbour::records {

AuditWriter::AuditWriter(std::string database) : database_(std::move(database)) {
  thread_ = std::thread([this] { run(); });
}

AuditWriter::~AuditWriter() {
  flush();
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void AuditWriter::add(const std::string& account, const std::string& action, const std::string& target,
                      const std::string& detail) {
  {
    const std::lock_guard lock(mutex_);
    queue_.push_back({records::utc_now(), account, action, target, detail});
    ++queued_;
  }
  wake_.notify_one();
}

bool AuditWriter::flush(double timeout_s) {
  std::unique_lock lock(mutex_);
  const std::uint64_t wanted = queued_;
  return written_.wait_for(lock, std::chrono::duration<double>(timeout_s), [&] { return done_ >= wanted; });
}

std::string AuditWriter::last_error() const {
  const std::lock_guard lock(mutex_);
  return last_error_;
}

void AuditWriter::run() {
  std::unique_ptr<records::RecordsStore> db;
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping with nothing left
    const AuditRow row = queue_.front();
    lock.unlock();
    std::string error;
    try {
      if (!db) db = std::make_unique<records::RecordsStore>(database_);
      db->audit(row);
    } catch (const std::exception& e) {
      error = e.what();
      db.reset();  // opened again for the next try
    }
    lock.lock();
    last_error_ = error;
    if (!error.empty()) {
      // kept at the front: tried again in a second (a stop does not wait for a database that is gone)
      if (wake_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; })) return;
      continue;
    }
    queue_.pop_front();
    ++done_;
    written_.notify_all();
  }
}

}  // namespace harbour::records
