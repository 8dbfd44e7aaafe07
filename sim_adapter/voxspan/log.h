// voxspan/log.h - the library's one logger. Messages go to stderr by default; a solver can
// route them into its own log with set_log_sink(). Level from VOXSPAN_LOG_LEVEL
// (error, warning, info, debug) or set_log_level(). Thread-safe.
#pragma once

#include <functional>
#include <sstream>
#include <string>
#include <string_view>

namespace voxspan {

enum class LogLevel { error = 0, warning = 1, info = 2, debug = 3 };

using LogSink = std::function<void(LogLevel, std::string_view message)>;

// Replaces the sink; an empty sink restores the default (stderr, prefixed "voxspan").
void set_log_sink(LogSink sink);
void set_log_level(LogLevel level);
LogLevel log_level();
// A tag put before every message of the default sink, e.g. "rank 3".
void set_log_tag(std::string tag);

void log_message(LogLevel level, std::string_view message);

// Parses "error", "warning", "info", "debug"; returns false on anything else.
bool parse_log_level(std::string_view text, LogLevel& level);

template <class... Parts> void log(LogLevel level, const Parts&... parts) {
  if (level > log_level()) return;
  std::ostringstream s;
  (s << ... << parts);
  log_message(level, s.str());
}
template <class... P> void log_error(const P&... p) { log(LogLevel::error, p...); }
template <class... P> void log_warning(const P&... p) { log(LogLevel::warning, p...); }
template <class... P> void log_info(const P&... p) { log(LogLevel::info, p...); }
template <class... P> void log_debug(const P&... p) { log(LogLevel::debug, p...); }

}  // namespace voxspan
