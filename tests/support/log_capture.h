// Captures the library's log messages for one scope (tests only).
#pragma once

#include <algorithm>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "voxspan/log.h"

namespace voxspan::test {

class LogCapture {
 public:
  LogCapture() {
    previous_level_ = log_level();
    set_log_level(LogLevel::debug);
    set_log_sink([this](LogLevel level, std::string_view message) {
      std::lock_guard lock(mutex_);
      messages_.emplace_back(level, std::string(message));
    });
  }
  ~LogCapture() {
    set_log_sink({});
    set_log_level(previous_level_);
  }
  std::vector<std::string> at(LogLevel level) const {
    std::lock_guard lock(mutex_);
    std::vector<std::string> out;
    for (const auto& [l, m] : messages_)
      if (l == level) out.push_back(m);
    return out;
  }
  std::string all() const {
    std::lock_guard lock(mutex_);
    std::string out;
    for (const auto& [l, m] : messages_) out += m + "\n";
    return out;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::pair<LogLevel, std::string>> messages_;
  LogLevel previous_level_;
};

}  // namespace voxspan::test
