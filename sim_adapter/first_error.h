// first_error.h (internal) - collects the error of a parallel loop over bad input: of all the
// problems found, the one with the smallest key (cell or particle index) is reported, so the
// message is the same on every run whatever the thread schedule.
#pragma once

#include <atomic>
#include <cstddef>
#include <limits>
#include <mutex>
#include <string>

#include "voxspan/error.h"

namespace voxspan::detail {

class FirstError {
 public:
  template <class... Parts> void offer(std::size_t key, const Parts&... parts) {
    std::lock_guard lock(mutex_);
    if (key >= key_) return;
    key_ = key;
    message_ = make_error(parts...).what();
    raised_.store(true, std::memory_order_relaxed);
  }
  bool raised() const { return raised_.load(std::memory_order_relaxed); }
  template <class E = Error> void throw_if_raised() const {
    if (raised()) throw E(message_);
  }

 private:
  std::mutex mutex_;
  std::size_t key_ = std::numeric_limits<std::size_t>::max();
  std::string message_;
  std::atomic<bool> raised_{false};
};

}  // namespace voxspan::detail
