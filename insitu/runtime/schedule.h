// insitu/runtime/schedule.h - which work a step needs, from the triggers of the config: the
// render trigger and each enabled output's own trigger. plan() is what the adapter calls first
// every step; when nothing is due it returns after a handful of compares per output
// (docs/benchmarks.md, "Runtime").
#pragma once

#include <cstdint>
#include <vector>

#include "insitu/config/config.h"
#include "insitu/config/trigger.h"

namespace voxspan {

struct StepPlan {
  bool render = false;        // classify, voxelize and shade every view
  std::vector<bool> outputs;  // due, per output of Config::outputs (in its order)

  bool any() const;
};

class Schedule {
 public:
  // The kinds' needs decide which outputs make a step a render step (insitu/runtime/registry.h).
  explicit Schedule(const Config& config);

  // A plan sized for this config, nothing due.
  StepPlan blank() const;
  // Once per solver step, steps non-decreasing; last_step when the solver says it is its last.
  // ORs what is due into `plan` (made by blank()): a second call for the same step with
  // last_step adds the `last` conditions. Allocates nothing.
  void plan(std::int64_t step, double time, bool last_step, StepPlan& plan);
  // The same into a fresh plan (tests, tools).
  StepPlan plan(std::int64_t step, double time, bool last_step = false);

 private:
  struct Entry {
    Trigger trigger;
    bool enabled;
    bool renders;  // its being due makes the step a render step
  };
  Trigger render_;
  bool has_views_;
  std::vector<Entry> outputs_;
};

}  // namespace voxspan
