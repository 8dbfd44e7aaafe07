// render/gl/pass_timer.h - the one way every pass is timed. A Scope covers the GL work issued
// (or the CPU work done) while it lives and adds its milliseconds to the pass's entry in
// FrameStats when collect() runs.
//   GPU timer queries where the context has real ones (NVIDIA): no stalls, results read once in
//   collect(); elsewhere (llvmpipe, whose queries read ~1 ns) glFinish before and after the
//   scope and a wall clock, so each scope measures exactly its own work.
// GPU scopes must not nest (GL has one GL_TIME_ELAPSED query active at a time); CPU scopes may
// sit inside anything.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "render/frame_stats.h"
#include "render/gl/objects.h"
#include "voxspan/stopwatch.h"

namespace voxspan::gl {

class PassTimer {
 public:
  // `gpu_timers`: Context::has_gpu_timers().
  explicit PassTimer(bool gpu_timers);

  class Scope {
   public:
    ~Scope();
    Scope(Scope&& o) noexcept;
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    Scope& operator=(Scope&&) = delete;

   private:
    friend class PassTimer;
    Scope(PassTimer* timer, std::size_t record, bool gpu);
    PassTimer* timer_;
    std::size_t record_;
    bool gpu_;
  };

  // Times GL work issued during the scope.
  [[nodiscard]] Scope gpu(std::string_view pass);
  // Times CPU work (wall clock, no glFinish).
  [[nodiscard]] Scope cpu(std::string_view pass);

  // Adds every finished scope to `stats` (waiting for query results), records the GPU memory
  // held now and its peak, and starts over.
  void collect(FrameStats& stats);
  bool uses_gpu_queries() const { return gpu_timers_; }

 private:
  struct Record {
    std::string pass;
    double ms = 0;
    int query = -1;   // index into queries_ when timed by a GPU query
    Stopwatch watch;  // CPU scopes and llvmpipe: from the scope's start
  };
  void finish(std::size_t record, bool gpu);

  bool gpu_timers_;
  bool gpu_scope_open_ = false;
  std::vector<Record> records_;
  std::vector<TimerQuery> queries_;  // reused from step to step
  std::size_t queries_used_ = 0;
};

}  // namespace voxspan::gl
