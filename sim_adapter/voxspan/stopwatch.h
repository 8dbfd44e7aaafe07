// voxspan/stopwatch.h - the one wall clock every CPU timing of the library reads (classification,
// the runtime's steps, the writer's jobs, the host scopes of render/recorder.h). Standard
// library only.
#pragma once

#include <chrono>

namespace voxspan {

class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}
  void restart() { start_ = Clock::now(); }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  double ms() const { return 1e3 * seconds(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

}  // namespace voxspan
