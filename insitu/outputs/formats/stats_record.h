// insitu/outputs/formats/stats_record.h - what one step cost and counted, as one JSON line.
//
// Generic on purpose: every pass adds named timings and counters, so a new pass needs no new
// field. A record has totals and one section per view, each a FrameStats (render/frame_stats.h),
// the very object the view's passes report into:
//   {"step":120,"time":0.6,"timings_ms":{"classify":3.1},"counters":{"particles":100000,
//    "boundary":31000,"dropped":0},"memory_mib":{"host_rss":812.4,"gpu":301.0},
//    "views":{"main":{"timings_ms":{"splat":40.2},"counters":{"spans":1203311}}}}
// Non-finite numbers are written as null (JSON has no NaN). Sections keep their storage
// between steps (zero() keeps every name), so a stable run allocates nothing here.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "render/frame_stats.h"

namespace voxspan {

struct StatsRecord {
  std::int64_t step = 0;
  double time = 0;
  FrameStats totals;
  std::vector<std::pair<std::string, FrameStats>> views;
  std::vector<std::pair<std::string, double>> memory_mib;  // "host_rss", "host_peak", "gpu"...
  // Why the step failed (a view, an output), written as "error" when not empty.
  std::string error;
  // In an MPI job (count > 1), the root's record: the totals' and the views' timings are the
  // slowest rank's and their counters the sum over the ranks; the means and what every rank
  // sent are here. Written as "ranks":{"count":N,"bytes_sent":[...],"timings_ms_mean":{...},
  // "views":{"<view>":{"timings_ms_mean":{...}}}}.
  struct Ranks {
    int count = 1;
    std::vector<std::int64_t> bytes_sent;  // per rank, on this step
    FrameStats totals_mean;
    std::vector<std::pair<std::string, FrameStats>> views_mean;
  } ranks;

  FrameStats& view(std::string_view name);  // created on first use
  void set_memory(std::string_view name, double mib);
  void clear();  // keeps the views (empty)
  void zero();   // every value to 0, every name kept (sections and memory entries)
};

std::string to_json_line(const StatsRecord& record);  // one line, '\n' included
// The same line appended to `out` (whose capacity a caller can reuse from step to step).
void append_json_line(const StatsRecord& record, std::string& out);

}  // namespace voxspan
