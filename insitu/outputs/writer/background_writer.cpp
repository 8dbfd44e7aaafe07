#include "insitu/outputs/writer/background_writer.h"

#include <exception>
#include <utility>

#include "insitu/outputs/writer/atomic_file.h"

#include "voxspan/log.h"

namespace voxspan {
namespace {
bool is_power_of_ten(std::uint64_t n) {
  while (n >= 10 && n % 10 == 0) n /= 10;
  return n == 1;
}
}  // namespace

BackgroundWriter::BackgroundWriter(std::size_t queue_size, QueuePolicy policy)
    : capacity_(queue_size == 0 ? 1 : queue_size), policy_(policy), ring_(capacity_) {
  thread_ = std::thread([this] { run(); });
}

BackgroundWriter::~BackgroundWriter() {
  drain();
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_all();
  thread_.join();
  WriterStats s = stats();
  if (s.failed > 1)
    log_warning("writer: ", s.failed, " of ", s.submitted,
                " files could not be written; the "
                "first failure: ",
                s.first_error);
  if (s.dropped > 0)
    log_warning("writer: ", s.dropped, " files were dropped because the writer queue (", capacity_,
                " jobs) was full; raise writer.queue_size or use when_full: wait");
}

void BackgroundWriter::keep_every_file() {
  std::lock_guard lock(mutex_);
  policy_ = QueuePolicy::wait;
}

bool BackgroundWriter::submit(std::string label, Job job) {
  std::unique_lock lock(mutex_);
  if (queued_ >= capacity_) {
    if (policy_ == QueuePolicy::drop) {
      std::uint64_t dropped = ++stats_.dropped;
      lock.unlock();
      if (is_power_of_ten(dropped))
        log_warning("writer queue full (", capacity_, " jobs): dropped ", label, "; ", dropped,
                    dropped == 1 ? " file dropped so far" : " files dropped so far");
      return false;
    }
    ++stats_.waits;
    space_ready_.wait(lock, [&] { return queued_ < capacity_; });
  }
  Entry& slot = ring_[(head_ + queued_) % capacity_];
  slot.label = std::move(label);
  slot.job = std::move(job);
  ++queued_;
  ++stats_.submitted;
  stats_.max_queued = std::max(stats_.max_queued, queued_);
  lock.unlock();
  work_ready_.notify_one();
  return true;
}

void BackgroundWriter::drain() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [&] { return queued_ == 0 && !busy_; });
}

WriterStats BackgroundWriter::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::size_t BackgroundWriter::queued() const {
  std::lock_guard lock(mutex_);
  return queued_;
}

void BackgroundWriter::record_failure(const std::string& label, const std::string& message,
                                      int kind) {
  std::unique_lock lock(mutex_);
  ++stats_.failed;
  ++failures_since_success_;
  if (stats_.first_error.empty()) stats_.first_error = message;
  if (!reported_.insert(kind).second) return;
  lock.unlock();
  log_error("writer: ", label, " not written: ", message,
            "; the run goes on, and further failures like this one are counted without a "
            "message");
}

void BackgroundWriter::run() {
  for (;;) {
    Entry entry;
    {
      std::unique_lock lock(mutex_);
      work_ready_.wait(lock, [&] { return stopping_ || queued_ > 0; });
      if (queued_ == 0) return;              // stopping, and drained
      entry.label.swap(ring_[head_].label);  // swaps keep both strings' storage alive
      entry.job = std::move(ring_[head_].job);
      ring_[head_].job = nullptr;
      head_ = (head_ + 1) % capacity_;
      --queued_;
      busy_ = true;
    }
    space_ready_.notify_one();
    bool ok = false;
    int kind = 0;
    std::string message;
    try {
      entry.job();
      ok = true;
    } catch (const WriteError& e) {
      message = e.what();
      kind = e.error_number();
    } catch (const std::exception& e) {
      message = e.what();
    } catch (...) {
      message = "unknown error";
    }
    if (ok) {
      std::unique_lock lock(mutex_);
      ++stats_.completed;
      if (std::uint64_t n = std::exchange(failures_since_success_, 0); n > 0) {
        lock.unlock();
        log_info("writer: a file was written again after ", n, " failed");
      }
    } else {
      record_failure(entry.label, message, kind);
    }
    entry.job = nullptr;  // free the job's data before reporting idle
    {
      std::lock_guard lock(mutex_);
      busy_ = false;
    }
    idle_.notify_all();
  }
}

}  // namespace voxspan
