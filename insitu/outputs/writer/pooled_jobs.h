// insitu/outputs/writer/pooled_jobs.h - an output's writes as background jobs on pooled slots: the
// solver's thread fills a slot (its vectors keep their capacity from the slot's last use,
// insitu/outputs/writer/slot_pool.h) and hands it to the writer, whose job writes it and gives it
// back. Counts what was handed over, written, and refused for want of a slot, and the writer
// thread's time in the jobs: what OutputTally reports.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>

#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/background_writer.h"
#include "insitu/outputs/writer/slot_pool.h"
#include "voxspan/stopwatch.h"

namespace voxspan {

template <class Slot> class PooledJobs {
 public:
  // `write` runs on the writer's thread; what it throws the writer counts as a failed file.
  PooledJobs(BackgroundWriter& writer, std::size_t slots, std::function<void(Slot&)> write)
      : writer_(writer), pool_(std::make_unique<SlotPool<Slot>>(slots)), write_(std::move(write)) {}

  // Fills a free slot with fill(Slot&) here and hands it to the writer. False when no slot is
  // free or the writer refused the job (its queue full under policy `drop`: it counts that).
  // What fill throws comes back to the caller, the slot freed.
  template <class Fill> bool submit(const char* label, Fill&& fill) {
    Slot* slot = pool_->acquire();
    if (slot == nullptr) {
      ++no_slot_;
      return false;
    }
    try {
      fill(*slot);
    } catch (...) {
      pool_->release(slot);
      throw;
    }
    // Two pointers fit std::function's small buffer: a job allocates nothing.
    const bool accepted = writer_.submit(label, [this, slot] { run(slot); });
    if (!accepted) pool_->release(slot);
    submitted_ += accepted;
    return accepted;
  }

  OutputTally tally() const {
    return {submitted_, written_.load(), no_slot_, 1e-6 * double(writer_microseconds_.load())};
  }

 private:
  void run(Slot* slot) {
    SlotLease<Slot> lease(*pool_, slot);
    const Stopwatch watch;
    try {
      write_(*slot);
    } catch (...) {
      add_time(watch);
      throw;
    }
    add_time(watch);
    ++written_;
  }
  void add_time(const Stopwatch& watch) {
    writer_microseconds_ += static_cast<std::int64_t>(1e6 * watch.seconds());
  }

  BackgroundWriter& writer_;
  std::unique_ptr<SlotPool<Slot>> pool_;
  std::function<void(Slot&)> write_;
  std::int64_t submitted_ = 0, no_slot_ = 0;
  std::atomic<std::int64_t> written_{0}, writer_microseconds_{0};
};

}  // namespace voxspan
