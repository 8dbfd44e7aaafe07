// insitu/outputs/writer/slot_pool.h - reusable buffers for the background writer's jobs.
//
// A job must own its data (the solver's memory changes at the next step), but copying into
// fresh vectors every render step would allocate every step. Instead the solver's thread
// acquires a slot, fills it (vectors keep their capacity from the slot's last use), hands a
// pointer to the job, and the job releases the slot when it ends. Slots are made on first need,
// at most `max_slots` of them: with a writer queue of Q jobs, at most Q + 1 jobs of one kind
// are in flight (Q queued, one running), so Q + 2 slots always leave one free.
// Thread-safe: acquire on the solver's thread, release on the writer's.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

namespace voxspan {

template <class T> class SlotPool {
 public:
  explicit SlotPool(std::size_t max_slots) : max_slots_(max_slots) {
    slots_.reserve(max_slots);
    free_.reserve(max_slots);
  }

  // A free slot, made when none is free; nullptr when all max_slots are in use.
  T* acquire() {
    std::lock_guard lock(mutex_);
    if (!free_.empty()) {
      T* slot = free_.back();
      free_.pop_back();
      return slot;
    }
    if (slots_.size() == max_slots_) return nullptr;
    slots_.push_back(std::make_unique<T>());
    return slots_.back().get();
  }

  void release(T* slot) {
    if (slot == nullptr) return;
    std::lock_guard lock(mutex_);
    free_.push_back(slot);
  }

  std::size_t slots_made() const {
    std::lock_guard lock(mutex_);
    return slots_.size();
  }

 private:
  const std::size_t max_slots_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<T>> slots_;
  std::vector<T*> free_;
};

// Releases a slot when the scope ends (a job that throws still gives its slot back).
template <class T> class SlotLease {
 public:
  SlotLease(SlotPool<T>& pool, T* slot) : pool_(pool), slot_(slot) {}
  ~SlotLease() { pool_.release(slot_); }
  SlotLease(const SlotLease&) = delete;
  SlotLease& operator=(const SlotLease&) = delete;
  T& operator*() const { return *slot_; }
  T* operator->() const { return slot_; }

 private:
  SlotPool<T>& pool_;
  T* slot_;
};

}  // namespace voxspan
