// render/gl/gpu_recorder.h - the GL renderer's Recorder (render/recorder.h): its device scopes
// time the GL work issued while they live.
//   GPU timer queries where the context has real ones (NVIDIA): no stalls, results read once in
//   collect(); elsewhere (llvmpipe, whose queries read ~1 ns) glFinish before and after the
//   scope and the wall clock, so that each scope measures exactly its own work.
// Device scopes must not nest (GL has one GL_TIME_ELAPSED query active at a time). collect()
// also records the GPU memory held now and its peak (render/gl/objects.h).
#pragma once

#include <vector>

#include "render/gl/objects.h"
#include "render/recorder.h"

namespace voxspan::gl {

class GpuRecorder final : public Recorder {
 public:
  // `gpu_timers`: Context::has_gpu_timers().
  GpuRecorder(FrameStats& stats, bool gpu_timers) : Recorder(stats), gpu_timers_(gpu_timers) {}
  explicit GpuRecorder(bool gpu_timers) : gpu_timers_(gpu_timers) {}
  bool uses_gpu_queries() const { return gpu_timers_; }

 private:
  int begin_device(StatName pass) override;
  void end_device(int timer) override;
  double device_ms(int timer) override;
  void end_collect(FrameStats& stats) override;

  bool gpu_timers_;
  bool scope_open_ = false;
  std::vector<TimerQuery> queries_;  // reused from step to step
  std::size_t queries_used_ = 0;
};

}  // namespace voxspan::gl
