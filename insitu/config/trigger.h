// insitu/config/trigger.h - when something happens: every N steps, every T of simulated time, on
// the first and on the last step, when a condition on the particles becomes true, any
// combination (OR).
//
// "Every N steps" and "every T" fire on the first call whose step (time) reaches the next
// multiple of N (T), so a solver with a variable time step, or one that calls only every few
// steps, never misses a multiple, and never fires twice for the same one. Times within
// 1e-9 T below a multiple count as reaching it (sums of dt rarely hit it exactly).
// is_due() is a few compares on the caller's thread: a non-render step costs nanoseconds.
//
// A condition (`when`, insitu/config/condition.h) fires on its rising edge: on a check where it
// holds after one where it did not (before the first check it did not), outside the cool-down
// after its last firing, and only the first time with `once`. Whether it holds is the
// schedule's to find from the particles (insitu/runtime/schedule.h); the trigger keeps the edge.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

namespace voxspan {

// Where the config gave a section ("run.yaml:12:5: views[2]"; empty for a default one), kept
// for messages. Not a setting: settings that differ only here are equal.
struct ConfigSource {
  std::string where;
  bool operator==(const ConfigSource&) const { return true; }
  // One of the section's keys for messages: "run.yaml:12:5: views[2].quantity", or `fallback`
  // (the key's path alone) for a section the config did not give.
  std::string key_path(std::string_view key, std::string_view fallback) const {
    return where.empty() ? std::string(fallback) : where + "." + std::string(key);
  }
};

struct TriggerSpec {
  std::int64_t every_steps = 0;     // 0: off
  double every_time = 0;            // simulated time units; 0: off
  bool first = false;               // the first call
  bool last = false;                // the call the solver marks as its last step
  std::string when{};               // a condition on the particles; empty: off
  bool once = false;                // the condition fires the first time only
  std::int64_t cooldown_steps = 0;  // after the condition fired, it cannot for this many steps
  double cooldown_time = 0;         // ... nor for this much simulated time
  ConfigSource source{};            // of `when`, for the messages of the steps

  bool never_fires() const {
    return every_steps <= 0 && every_time <= 0 && !first && !last && when.empty();
  }
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

  // Whether the condition is to be checked on the next step: there is one, and `once` has not
  // used it up.
  bool checks_condition() const { return !spec_.when.empty() && !(spec_.once && fired_); }
  // Whether the condition fires, given whether it holds on this step (after is_due() for it).
  bool condition_fires(std::int64_t step, double time, bool holds);

  const TriggerSpec& spec() const { return spec_; }
  void restart() {
    started_ = false;
    held_ = fired_ = false;
  }

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
  bool held_ = false;          // the condition held on the previous check
  bool fired_ = false;         // the condition has fired (since the start or a restart)
  std::int64_t fired_step_ = 0;
  double fired_time_ = 0;
};

}  // namespace voxspan
