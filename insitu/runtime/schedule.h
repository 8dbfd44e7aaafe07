// insitu/runtime/schedule.h - which work a step needs, from the triggers of the config: the
// render trigger and each enabled output's own trigger. plan() is what the adapter calls first
// every step; when nothing is due it returns after a handful of compares per output
// (docs/benchmarks.md, "Runtime"). Triggers with a condition (`when`) need the step's
// particles as well: plan() then marks the plan as waiting for decide(), which reduces the
// particles (insitu/runtime/particle_reductions.h) and fires the conditions that became true.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "insitu/config/condition.h"
#include "insitu/config/config.h"
#include "insitu/config/trigger.h"
#include "insitu/runtime/particle_reductions.h"

namespace voxspan {

class Communicator;

struct StepPlan {
  bool render = false;        // classify, voxelize and shade every view
  std::vector<bool> outputs;  // due, per output of Config::outputs (in its order)
  bool conditions = false;    // conditions wait for the step's particles (Schedule::decide)

  bool any() const;
  void clear();
};

class Schedule {
 public:
  // The kinds' needs decide which outputs make a step a render step (insitu/runtime/registry.h).
  // `comm`: the job's, whose ranks reduce the conditions' particles together (null: one
  // process). Throws voxspan::Error for a condition that does not compile (a config made in
  // code; a file's are checked when read).
  explicit Schedule(const Config& config, Communicator* comm = nullptr);
  ~Schedule();

  // A plan sized for this config, nothing due.
  StepPlan blank() const;
  // Once per solver step, steps non-decreasing; last_step when the solver says it is its last.
  // ORs what is due into `plan` (made by blank()): a second call for the same step with
  // last_step adds the `last` conditions. Sets plan.conditions when a condition is to be
  // checked on this step. Allocates nothing.
  void plan(std::int64_t step, double time, bool last_step, StepPlan& plan);
  // The same into a fresh plan (tests, tools).
  StepPlan plan(std::int64_t step, double time, bool last_step = false);
  // After plan() set plan.conditions: reduces the particles the conditions name, ORs the
  // triggers whose condition fires into `plan` and clears plan.conditions. Under MPI a
  // collective: every rank calls it on the same steps. Allocates nothing (but the message,
  // said once, of an attribute the solver does not pass: that condition is false).
  void decide(std::int64_t step, double time, const ParticleView& particles, StepPlan& plan);

 private:
  struct Entry {
    Trigger trigger;
    bool enabled;
    bool renders;        // its being due makes the step a render step
    int condition = -1;  // into conditions_
  };
  struct Watched {
    Condition condition;
    std::vector<std::size_t> reductions;  // per input, into the reductions' list
    std::string key;                      // "run.yaml:3:9: trigger.when", for messages
    bool told = false;                    // its missing attribute is said (once a key)
  };
  void add(const TriggerSpec& spec, bool enabled, bool renders, const Config& config);
  void fire(std::size_t entry, StepPlan& plan) const;
  bool holds(Watched& w, std::int64_t step, double time, const ParticleView& particles);

  std::vector<Entry> entries_;  // the render trigger, then the outputs'
  std::vector<Watched> conditions_;
  std::vector<Reduction> reduction_list_;  // every condition's, each once
  std::unique_ptr<ParticleReductions> reductions_;
  std::vector<char> wanted_;  // per reduction, this step
  bool reports_;              // logs (one rank of a job)
};

}  // namespace voxspan
