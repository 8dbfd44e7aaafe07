// insitu/stats.h - what one step cost and counted, as one JSON line.
//
// Generic on purpose: every pass adds named timings and counters, so a new pass needs no new
// field. A record has totals and one section per view:
//   {"step":120,"time":0.6,"timings_ms":{"classify":3.1},"counters":{"particles":100000,
//    "boundary":31000,"dropped":0},"memory_mib":{"host_rss":812.4,"gpu":301.0},
//    "views":{"main":{"timings_ms":{"splat":40.2},"counters":{"spans":1203311}}}}
// Non-finite numbers are written as null (JSON has no NaN). Sections keep their storage
// between steps (clear() keeps capacity), so a stable run allocates nothing here.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace voxspan {

struct StatsSection {
  std::vector<std::pair<std::string, double>> timings_ms;
  std::vector<std::pair<std::string, std::int64_t>> counters;

  // Adding a name twice accumulates (a pass run per tile adds its time per tile).
  void add_time(std::string_view name, double ms);
  void add_count(std::string_view name, std::int64_t n);
  double time(std::string_view name) const;          // 0 when absent
  std::int64_t count(std::string_view name) const;   // 0 when absent
  void clear();
  // Every value to 0, the names kept: a record refilled each step allocates nothing.
  void zero();
  bool empty() const { return timings_ms.empty() && counters.empty(); }
};

struct StatsRecord {
  std::int64_t step = 0;
  double time = 0;
  StatsSection totals;
  std::vector<std::pair<std::string, StatsSection>> views;
  std::vector<std::pair<std::string, double>> memory_mib;  // "host_rss", "host_peak", "gpu"...

  StatsSection& view(std::string_view name);  // created on first use
  void set_memory(std::string_view name, double mib);
  void clear();  // keeps the names' storage
  void zero();   // every value to 0, every name kept (sections and memory entries)
};

std::string to_json_line(const StatsRecord& record);  // one line, '\n' included
// The same line appended to `out` (whose capacity a caller can reuse from step to step).
void append_json_line(const StatsRecord& record, std::string& out);

// Adds the wall time of its scope to a section: { ScopedTiming t(stats.totals, "classify"); }
class ScopedTiming {
 public:
  ScopedTiming(StatsSection& section, std::string_view name)
      : section_(section), name_(name), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTiming() {
    std::chrono::duration<double, std::milli> d = std::chrono::steady_clock::now() - start_;
    section_.add_time(name_, d.count());
  }
  ScopedTiming(const ScopedTiming&) = delete;
  ScopedTiming& operator=(const ScopedTiming&) = delete;

 private:
  StatsSection& section_;
  std::string_view name_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace voxspan
