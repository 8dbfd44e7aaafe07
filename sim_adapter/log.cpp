#include "voxspan/log.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>

#include "voxspan/version.h"

namespace voxspan {
namespace {

struct LoggerState {
  std::mutex mutex;
  LogSink sink;
  std::string tag;
  std::atomic<LogLevel> level{initial_level()};

  static LogLevel initial_level() {
    LogLevel level = LogLevel::warning;
    if (const char* env = std::getenv("VOXSPAN_LOG_LEVEL")) {
      if (!parse_log_level(env, level))
        std::fprintf(stderr,
                     "voxspan: ignoring VOXSPAN_LOG_LEVEL=%s (expected error, warning, "
                     "info or debug)\n",
                     env);
    }
    return level;
  }
};

LoggerState& state() {
  static LoggerState s;
  return s;
}

const char* level_name(LogLevel level) {
  switch (level) {
    case LogLevel::error: return "error";
    case LogLevel::warning: return "warning";
    case LogLevel::info: return "info";
    case LogLevel::debug: return "debug";
  }
  return "?";
}

}  // namespace

const char* version() { return VOXSPAN_VERSION_STRING; }

bool parse_log_level(std::string_view text, LogLevel& level) {
  for (LogLevel l : {LogLevel::error, LogLevel::warning, LogLevel::info, LogLevel::debug}) {
    if (text == level_name(l)) {
      level = l;
      return true;
    }
  }
  return false;
}

void set_log_sink(LogSink sink) {
  std::lock_guard lock(state().mutex);
  state().sink = std::move(sink);
}

void set_log_level(LogLevel level) { state().level.store(level, std::memory_order_relaxed); }

// Relaxed: the level is a filter, not a synchronisation point.
LogLevel log_level() { return state().level.load(std::memory_order_relaxed); }

void set_log_tag(std::string tag) {
  std::lock_guard lock(state().mutex);
  state().tag = std::move(tag);
}

void log_message(LogLevel level, std::string_view message) {
  LoggerState& s = state();
  std::lock_guard lock(s.mutex);
  if (level > log_level()) return;
  if (s.sink) {
    s.sink(level, message);
    return;
  }
  std::fprintf(stderr, "voxspan%s%s %s: %.*s\n", s.tag.empty() ? "" : " ", s.tag.c_str(),
               level_name(level), static_cast<int>(message.size()), message.data());
}

}  // namespace voxspan
