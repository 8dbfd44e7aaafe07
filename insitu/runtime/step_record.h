// insitu/runtime/step_record.h - one step's stats line (insitu/outputs/formats/stats_record.h) from
// what the step measured: the adapter's classification (voxspan/adapter.h StepStats), every view's
// FrameStats (time per pass, counts), the writer's counters and the memory in use.
//
//   totals.timings_ms  classify, compact, render, outputs, in_situ (all of the step's in-situ
//                      work on the solver's thread)
//   totals.counters    particles, owned, boundary, dropped (= dropped_nonfinite +
//                      not_in_grid), culled (all views), cells, cells_inner_empty,
//                      cells_inner_full, writer_completed, writer_failed, writer_dropped
//   memory_mib         host_rss, host_peak, gpu, gpu_peak
//   views.<name>       timings_ms per pass; counters as the renderer reports them plus
//                      particles.culled (behind the camera or outside the view)
// Filling a record whose names exist already allocates nothing.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "insitu/outputs/formats/stats_record.h"
#include "insitu/outputs/writer/background_writer.h"
#include "insitu/runtime/host_memory.h"
#include "render/frame_stats.h"
#include "voxspan/adapter.h"

namespace voxspan {

struct StepRecordInput {
  std::int64_t step = 0;
  double time = 0;
  const StepStats* adapter = nullptr;
  double render_ms = 0, outputs_ms = 0, process_ms = 0;  // the pipeline's share
  const WriterStats* writer = nullptr;
  HostMemory memory;
};

// All of a step's in-situ work on the solver's thread: the adapter's classification and
// compaction, and the pipeline's process().
inline double in_situ_ms(const StepStats& adapter, double process_ms) {
  return 1e3 * (adapter.seconds_classify + adapter.seconds_compact) + process_ms;
}

// Fills the record's totals and memory. Its view sections are the views' own FrameStats (the
// passes reported into them while rendering); each gets its particles.culled count here.
void fill_step_record(const StepRecordInput& in, StatsRecord& record);

}  // namespace voxspan
