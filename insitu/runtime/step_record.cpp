#include "insitu/runtime/step_record.h"

#include <algorithm>

namespace voxspan {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

std::int64_t culled(const FrameStats& s) {
  return s.count("particles.culled_behind") + s.count("particles.culled_outside");
}

}  // namespace

void fill_step_record(const StepRecordInput& in, StatsRecord& r) {
  r.step = in.step;
  r.time = in.time;
  FrameStats& t = r.totals;
  t.zero();
  const StepStats& a = *in.adapter;
  const ClassifyCounts& c = a.counts;
  t.add_time("classify", 1e3 * a.seconds_classify);
  t.add_time("compact", 1e3 * a.seconds_compact);
  t.add_time("render", in.render_ms);
  t.add_time("outputs", in.outputs_ms);
  t.add_time("in_situ", in_situ_ms(a, in.process_ms));
  t.add_count("particles", std::int64_t(c.particles));
  t.add_count("owned", std::int64_t(c.owned));
  t.add_count("boundary", std::int64_t(c.boundary));
  t.add_count("dropped", std::int64_t(c.dropped_nonfinite + c.not_in_grid));
  t.add_count("dropped_nonfinite", std::int64_t(c.dropped_nonfinite));
  t.add_count("not_in_grid", std::int64_t(c.not_in_grid));
  std::int64_t all_culled = 0, gpu = 0, gpu_peak = 0;
  for (auto& [name, v] : r.views) {
    v.set_count("particles.culled", culled(v));
    all_culled += culled(v);
    gpu = std::max(gpu, v.gpu_bytes);
    gpu_peak = std::max(gpu_peak, v.gpu_peak_bytes);
  }
  t.add_count("culled", all_culled);
  t.add_count("cells", std::int64_t(c.cells));
  t.add_count("cells_inner_empty", std::int64_t(c.cells_inner_empty));
  t.add_count("cells_inner_full", std::int64_t(c.cells_inner_full));
  if (in.writer != nullptr) {
    t.add_count("writer_completed", std::int64_t(in.writer->completed));
    t.add_count("writer_failed", std::int64_t(in.writer->failed));
    t.add_count("writer_dropped", std::int64_t(in.writer->dropped));
  }
  r.set_memory("host_rss", double(in.memory.rss_bytes) / kMiB);
  r.set_memory("host_peak", double(in.memory.peak_bytes) / kMiB);
  r.set_memory("gpu", double(gpu) / kMiB);
  r.set_memory("gpu_peak", double(gpu_peak) / kMiB);
}

}  // namespace voxspan
