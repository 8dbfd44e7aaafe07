// insitu/config/trigger.h - when something happens: every N steps, every T of simulated time, on
// the first and on the last step, any combination (OR).
//
// "Every N steps" and "every T" fire on the first call whose step (time) reaches the next
// multiple of N (T), so a solver with a variable time step, or one that calls only every few
// steps, never misses a multiple, and never fires twice for the same one. Times within
// 1e-9 T below a multiple count as reaching it (sums of dt rarely hit it exactly).
// is_due() is a few compares on the caller's thread: a non-render step costs nanoseconds.
#pragma once

#include <cstdint>
#include <limits>

namespace voxspan {

struct TriggerSpec {
  std::int64_t every_steps = 0;  // 0: off
  double every_time = 0;         // simulated time units; 0: off
  bool first = false;            // the first call
  bool last = false;             // the call the solver marks as its last step

  bool never_fires() const { return every_steps <= 0 && every_time <= 0 && !first && !last; }
  bool operator==(const TriggerSpec&) const = default;
};

class Trigger {
 public:
  Trigger() = default;
  explicit Trigger(const TriggerSpec& spec) : spec_(spec) {}

  // Call once per step, with non-decreasing steps; a step below the previous one (a restart
  // from an earlier checkpoint) starts the schedule again from there.
  bool is_due(std::int64_t step, double time, bool last_step = false) {
    if (started_ && step < last_step_seen_) restart();
    bool due = (spec_.first && !started_) || (spec_.last && last_step);
    if (!started_) start(step, time);
    last_step_seen_ = step;
    if (spec_.every_steps > 0 && step >= next_step_) {
      due = true;
      next_step_ = (floor_div(step, spec_.every_steps) + 1) * spec_.every_steps;
    }
    if (spec_.every_time > 0) {
      if (time_pending_) start_time(time);
      if (time >= next_time_ - tolerance_) {
        due = true;
        advance_time(time);
      }
    }
    return due;
  }

  const TriggerSpec& spec() const { return spec_; }
  void restart() { started_ = false; }

 private:
  static std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    std::int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
  }
  void start(std::int64_t step, double time);
  void start_time(double time);
  void advance_time(double time);

  TriggerSpec spec_;
  bool started_ = false;
  std::int64_t last_step_seen_ = 0;
  std::int64_t next_step_ = 0;
  double next_time_ = std::numeric_limits<double>::infinity();
  double tolerance_ = 0;
  bool time_pending_ = false;  // no finite time seen yet
};

}  // namespace voxspan
