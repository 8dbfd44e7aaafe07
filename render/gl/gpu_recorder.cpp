#include "render/gl/gpu_recorder.h"

#include "voxspan/error.h"

namespace voxspan::gl {

int GpuRecorder::begin_device(StatName pass) {
  if (scope_open_)
    throw make_error("GpuRecorder: device scope '", pass.text, "' opened inside another");
  scope_open_ = true;
  if (!gpu_timers_) {
    glFinish();  // the scope measures its own work only, not what was queued before it
    return -1;
  }
  if (queries_used_ == queries_.size()) queries_.emplace_back();
  queries_[queries_used_].begin();
  return static_cast<int>(queries_used_++);
}

void GpuRecorder::end_device(int timer) {
  scope_open_ = false;
  if (timer >= 0) queries_[static_cast<std::size_t>(timer)].end();
  else glFinish();
}

double GpuRecorder::device_ms(int timer) {
  return queries_[static_cast<std::size_t>(timer)].milliseconds();
}

void GpuRecorder::end_collect(FrameStats& stats) {
  queries_used_ = 0;
  const MemoryUsage memory = memory_usage();
  stats.gpu_bytes = memory.current_bytes;
  stats.gpu_peak_bytes = memory.peak_bytes;
}

}  // namespace voxspan::gl
