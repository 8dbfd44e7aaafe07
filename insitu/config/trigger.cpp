#include "insitu/config/trigger.h"

#include <cmath>

namespace voxspan {

// The first call's own step/time fires when it is itself a multiple (step 0, time 0).
void Trigger::start(std::int64_t step, double time) {
  started_ = true;
  if (spec_.every_steps > 0) {
    std::int64_t n = spec_.every_steps;
    next_step_ = floor_div(step + n - 1, n) * n;  // ceil(step / n) * n
  }
  if (spec_.every_time > 0) {
    tolerance_ = 1e-9 * spec_.every_time;
    time_pending_ = true;
    next_time_ = std::numeric_limits<double>::infinity();
    start_time(time);
  }
}

// Until the solver reports a finite time, the time schedule has not started.
void Trigger::start_time(double time) {
  if (!std::isfinite(time)) return;
  time_pending_ = false;
  next_time_ = std::ceil((time - tolerance_) / spec_.every_time) * spec_.every_time;
}

void Trigger::advance_time(double time) {
  if (!std::isfinite(time)) return;
  double k = std::floor((time + tolerance_) / spec_.every_time);
  next_time_ = (k + 1) * spec_.every_time;
}

// A rising edge inside the cool-down is lost, not put off: the condition must fall and rise
// again. A time the solver has not made finite yet does not end a cool-down in time.
bool Trigger::condition_fires(std::int64_t step, double time, bool holds) {
  const bool rising = holds && !held_;
  held_ = holds;
  if (!rising || !checks_condition()) return false;
  if (fired_) {
    if (step < fired_step_ + spec_.cooldown_steps) return false;
    if (spec_.cooldown_time > 0 && std::isfinite(fired_time_) &&
        !(time >= fired_time_ + spec_.cooldown_time - 1e-9 * spec_.cooldown_time))
      return false;
  }
  fired_ = true;
  fired_step_ = step;
  fired_time_ = time;
  return true;
}

}  // namespace voxspan
