// insitu/outputs/writer/background_writer.h - one thread that writes files while the solver goes
// on.
//
// submit() hands over a job that owns its data (the solver's memory changes at the next
// step). The queue is bounded: when full, policy `wait` blocks the caller until a slot frees,
// policy `drop` returns false at once and counts the drop (a warning at the 1st, 10th, 100th...
// drop). A job reports failure by throwing (AtomicFile throws WriteError with errno): the first
// failure of each kind (errno; anything else is one kind) is logged as an error, later ones
// are only counted, so a full disk gives one message, not one per frame, even when small
// writes still squeeze in between; the summary comes when the writer closes. Nothing a job
// throws reaches the solver.
// drain() waits until every submitted job is done; the destructor drains, then stops.
// The queue is a ring of queue_size slots made once: submitting allocates nothing beyond what
// the caller's label and job hold (a job whose captures fit std::function's small buffer,
// e.g. two pointers, holds nothing on the heap).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "insitu/config/config.h"

namespace voxspan {

struct WriterStats {
  std::uint64_t submitted = 0;  // accepted into the queue
  std::uint64_t completed = 0;  // ran without throwing
  std::uint64_t failed = 0;     // threw
  std::uint64_t dropped = 0;    // refused because the queue was full (policy drop)
  std::uint64_t waits = 0;      // submits that blocked on a full queue (policy wait)
  std::size_t max_queued = 0;   // deepest the queue has been
  std::string first_error;      // the first failure's message
};

class BackgroundWriter {
 public:
  using Job = std::function<void()>;

  BackgroundWriter(std::size_t queue_size, QueuePolicy policy);
  explicit BackgroundWriter(const WriterConfig& config)
      : BackgroundWriter(static_cast<std::size_t>(config.queue_size), config.when_full) {}
  ~BackgroundWriter();
  BackgroundWriter(const BackgroundWriter&) = delete;
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;

  // label names the job in messages ("frame main_00000120.png"). Returns false when dropped.
  bool submit(std::string label, Job job);
  // Blocks until the queue is empty and no job runs.
  void drain();
  // From now on a full queue waits, whatever the policy: the solver's last step, whose files
  // finish() waits for anyway (dropping them would lose the run's last pictures for nothing).
  void keep_every_file();
  WriterStats stats() const;
  std::size_t queued() const;

 private:
  struct Entry {
    std::string label;
    Job job;
  };
  void run();
  void record_failure(const std::string& label, const std::string& message, int kind);

  const std::size_t capacity_;
  QueuePolicy policy_;  // guarded by mutex_
  mutable std::mutex mutex_;
  std::condition_variable work_ready_;   // writer thread waits for jobs
  std::condition_variable space_ready_;  // submitters wait for room (policy wait)
  std::condition_variable idle_;         // drain waits for the end of work
  std::vector<Entry> ring_;  // capacity_ slots; queued jobs are [head_, head_ + queued_)
  std::size_t head_ = 0;
  std::size_t queued_ = 0;
  bool busy_ = false;
  bool stopping_ = false;
  std::set<int> reported_;  // error kinds already logged (errno; 0 for anything else)
  std::uint64_t failures_since_success_ = 0;
  WriterStats stats_;
  std::thread thread_;
};

}  // namespace voxspan
