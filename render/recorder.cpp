#include "render/recorder.h"

namespace voxspan {

Recorder::Scope::Scope(Scope&& o) noexcept : recorder_(o.recorder_), record_(o.record_) {
  o.recorder_ = nullptr;
}

Recorder::Scope::~Scope() {
  if (recorder_ != nullptr) recorder_->close(record_);
}

Recorder::Scope Recorder::host(StatName pass) { return open(pass, false); }

Recorder::Scope Recorder::device(StatName pass) { return open(pass, true); }

Recorder::Scope Recorder::open(StatName pass, bool device) {
  // The device timer starts first: on llvmpipe it waits for the work queued before the scope.
  const int timer = device ? begin_device(pass) : -1;
  records_.push_back(Record{pass, device, timer, 0, Stopwatch()});
  return Scope(this, records_.size() - 1);
}

void Recorder::close(std::size_t record) {
  Record& r = records_[record];
  if (r.device) end_device(r.timer);
  if (r.timer < 0) r.ms = r.watch.ms();
}

void Recorder::collect() {
  for (const Record& r : records_)
    stats_->add_time(r.pass, r.timer >= 0 ? device_ms(r.timer) : r.ms);
  records_.clear();
  end_collect(*stats_);
}

}  // namespace voxspan
