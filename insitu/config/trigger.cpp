// A trigger: its keys in the config (trigger_section) and its schedule over the steps.
#include "insitu/config/trigger.h"

#include <cmath>
#include <limits>

#include "insitu/config/settings.h"
#include "insitu/config/yaml_reader.h"

namespace voxspan {
namespace {

using schema::Section;
using yaml::MapReader;

constexpr std::int64_t kNoLimit = std::numeric_limits<std::int64_t>::max();

bool has_condition(const TriggerSpec& t) { return !t.when.empty(); }

// A condition's own keys need the condition; its place is kept for the steps' messages.
void check_trigger(MapReader& r, TriggerSpec& t) {
  if (r.has("when")) {
    if (t.when.empty()) r.checker().error(r.find("when"), r.path("when"), "must not be empty");
    t.source.where = r.checker().where(r.find("when").Mark(), r.path("when"));
    return;
  }
  for (const char* key : {"once", "cooldown_steps", "cooldown_time"})
    if (r.has(key))
      r.checker().error(r.find(key), r.path(key), "is for a condition: set `when` or remove it");
}

}  // namespace

const Section<TriggerSpec>& trigger_section() {
  using T = TriggerSpec;
  static const Section<T> s{
      "trigger",
      {schema::integer("every_steps", &T::every_steps, std::int64_t{0}, kNoLimit,
                       "on the first step at or past each multiple of N; 0: off"),
       schema::number("every_time", &T::every_time, schema::at_least(0),
                      "on the first step whose simulated time reaches each multiple of T "
                      "(variable time steps: never misses a multiple, never fires twice for "
                      "one; 1e-9 T of slack for sums of dt); 0: off"),
       schema::flag("first", &T::first, "the first step the runtime sees"),
       schema::flag("last", &T::last, "the step the solver marks as its last"),
       schema::text("when", &T::when,
                    "a condition on the particles (`max(velocity) > 1 and time > 0.05`): "
                    "fires when it becomes true; checked on every step, at the cost of a pass "
                    "over the particles (docs/runtime.md, \"Triggers on conditions\")")
           .default_shown_as("none")
           .only_when(has_condition),
       schema::flag("once", &T::once, "with `when`: the condition fires the first time only")
           .only_when(has_condition),
       schema::integer("cooldown_steps", &T::cooldown_steps, std::int64_t{0}, kNoLimit,
                       "with `when`: steps after the condition fired during which it cannot "
                       "fire (a rising edge there is lost)")
           .only_when(has_condition),
       schema::number("cooldown_time", &T::cooldown_time, schema::at_least(0),
                      "with `when`: the same in simulated time")
           .only_when(has_condition)},
      check_trigger};
  return s;
}

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
