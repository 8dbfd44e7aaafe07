// insitu/step_record.h - one step's stats line (insitu/stats.h) from what the step measured:
// the adapter's classification (voxspan/adapter.h StepStats), every view's FrameStats (time
// per pass, counts), the writer's counters and the memory in use.
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

#include "insitu/background_writer.h"
#include "insitu/host_memory.h"
#include "insitu/stats.h"
#include "render/frame_stats.h"
#include "voxspan/adapter.h"

namespace voxspan {

struct ViewRecordSource {
  const std::string* name;
  const FrameStats* stats;
};

struct StepRecordInput {
  std::int64_t step = 0;
  double time = 0;
  const StepStats* adapter = nullptr;
  double render_ms = 0, outputs_ms = 0, process_ms = 0;  // the pipeline's share
  std::span<const ViewRecordSource> views;
  const WriterStats* writer = nullptr;
  HostMemory memory;
};

void fill_step_record(const StepRecordInput& in, StatsRecord& record);

// Every value to 0, the names kept, so a FrameStats reused per step allocates nothing.
void zero(FrameStats& stats);

}  // namespace voxspan
