#include "render/gl/pass_timer.h"

#include "voxspan/error.h"

namespace voxspan::gl {

PassTimer::PassTimer(bool gpu_timers) : gpu_timers_(gpu_timers) {}

PassTimer::Scope::Scope(PassTimer* timer, std::size_t record, bool gpu)
    : timer_(timer), record_(record), gpu_(gpu) {}

PassTimer::Scope::Scope(Scope&& o) noexcept : timer_(o.timer_), record_(o.record_), gpu_(o.gpu_) {
  o.timer_ = nullptr;
}

PassTimer::Scope::~Scope() {
  if (timer_ != nullptr) timer_->finish(record_, gpu_);
}

PassTimer::Scope PassTimer::gpu(std::string_view pass) {
  if (gpu_scope_open_)
    throw make_error("PassTimer: GPU scope '", pass, "' opened inside another GPU scope");
  gpu_scope_open_ = true;
  Record r;
  r.pass = std::string(pass);
  if (gpu_timers_) {
    if (queries_used_ == queries_.size()) queries_.emplace_back();
    r.query = static_cast<int>(queries_used_++);
    queries_[static_cast<std::size_t>(r.query)].begin();
  } else {
    glFinish();  // the scope measures its own work only, not what was queued before it
    r.watch.restart();
  }
  records_.push_back(std::move(r));
  return Scope(this, records_.size() - 1, true);
}

PassTimer::Scope PassTimer::cpu(std::string_view pass) {
  Record r;
  r.pass = std::string(pass);
  r.watch.restart();
  records_.push_back(std::move(r));
  return Scope(this, records_.size() - 1, false);
}

void PassTimer::finish(std::size_t record, bool gpu) {
  Record& r = records_[record];
  if (gpu) {
    gpu_scope_open_ = false;
    if (r.query >= 0) {
      queries_[static_cast<std::size_t>(r.query)].end();
      return;
    }
    glFinish();
  }
  r.ms = r.watch.ms();
}

void PassTimer::collect(FrameStats& stats) {
  for (Record& r : records_) {
    if (r.query >= 0) r.ms = queries_[static_cast<std::size_t>(r.query)].milliseconds();
    stats.add_time(r.pass, r.ms);
  }
  records_.clear();
  queries_used_ = 0;
  const MemoryUsage memory = memory_usage();
  stats.gpu_bytes = memory.current_bytes;
  stats.gpu_peak_bytes = memory.peak_bytes;
}

}  // namespace voxspan::gl
