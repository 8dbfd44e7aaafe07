#include "insitu/runtime/schedule.h"

#include <algorithm>

#include "insitu/parallel/communicator.h"
#include "insitu/runtime/registry.h"
#include "insitu/views/view_attributes.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {

bool StepPlan::any() const {
  return render || std::find(outputs.begin(), outputs.end(), true) != outputs.end();
}

void StepPlan::clear() {
  render = conditions = false;
  std::fill(outputs.begin(), outputs.end(), false);
}

Schedule::Schedule(const Config& config, Communicator* comm)
    : reports_(comm == nullptr || comm->root()) {
  add(config.trigger, !config.views.empty(), true, config);
  for (const ConfiguredOutput& o : config.outputs) {
    const ViewNeeds needs = registered_output_kind(o.kind).needs;
    // An output of the views' products has nothing to write without views.
    add(o.settings->trigger, o.settings->enabled && (!config.views.empty() || !needs.any()),
        needs.any(), config);
  }
  reductions_ = std::make_unique<ParticleReductions>(reduction_list_, config.boxes, comm);
  wanted_.assign(reduction_list_.size(), 0);
}

Schedule::~Schedule() = default;

void Schedule::add(const TriggerSpec& spec, bool enabled, bool renders, const Config& config) {
  entries_.push_back({Trigger(spec), enabled, renders});
  if (!enabled || spec.when.empty()) return;
  const std::string key = spec.source.where.empty() ? "trigger.when" : spec.source.where;
  try {
    Watched w{Condition(spec.when, config.constants, config.boxes), {}, key};
    for (const Reduction& r : w.condition.reductions()) {
      auto at = std::find(reduction_list_.begin(), reduction_list_.end(), r);
      if (at == reduction_list_.end()) at = reduction_list_.insert(at, r);
      w.reductions.push_back(std::size_t(at - reduction_list_.begin()));
    }
    entries_.back().condition = int(conditions_.size());
    conditions_.push_back(std::move(w));
  } catch (const ConditionError& e) {
    throw make_error(key, " \"", spec.when, "\": ", e.what(), " (at character ", e.position + 1,
                     ")");
  }
}

StepPlan Schedule::blank() const {
  return {false, std::vector<bool>(entries_.size() - 1, false), false};
}

void Schedule::fire(std::size_t entry, StepPlan& plan) const {
  if (entry == 0) {
    plan.render = true;
    return;
  }
  plan.outputs[entry - 1] = true;
  plan.render = plan.render || entries_[entry].renders;
}

void Schedule::plan(std::int64_t step, double time, bool last_step, StepPlan& plan) {
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    Entry& entry = entries_[e];
    if (!entry.enabled) continue;
    if (entry.trigger.is_due(step, time, last_step)) fire(e, plan);
    plan.conditions = plan.conditions || entry.trigger.checks_condition();
  }
}

StepPlan Schedule::plan(std::int64_t step, double time, bool last_step) {
  StepPlan p = blank();
  plan(step, time, last_step, p);
  return p;
}

void Schedule::decide(std::int64_t step, double time, const ParticleView& particles,
                      StepPlan& plan) {
  if (!plan.conditions) return;
  plan.conditions = false;
  std::fill(wanted_.begin(), wanted_.end(), 0);
  for (const Entry& e : entries_)
    if (e.enabled && e.condition >= 0 && e.trigger.checks_condition())
      for (std::size_t r : conditions_[std::size_t(e.condition)].reductions) wanted_[r] = 1;
  reductions_->run(particles, wanted_);
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    Entry& entry = entries_[e];
    if (!entry.enabled || entry.condition < 0 || !entry.trigger.checks_condition()) continue;
    const bool now = holds(conditions_[std::size_t(entry.condition)], step, time, particles);
    if (entry.trigger.condition_fires(step, time, now)) fire(e, plan);
  }
}

// A reduction whose attribute some rank lacks makes the condition false; the rank that logs
// says so once, with what its solver passes.
bool Schedule::holds(Watched& w, std::int64_t step, double time, const ParticleView& particles) {
  const std::span<double> inputs = w.condition.inputs();
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::size_t r = w.reductions[i];
    if (!reductions_->missing(r)) {
      inputs[i] = reductions_->value(r);
      continue;
    }
    if (!w.told && reports_) {
      // Outputs that follow the render trigger have its condition, and its mistake, too.
      for (Watched& same : conditions_) same.told = same.told || same.key == w.key;
      std::string message = w.key + ": another rank's solver passes no attribute \"" +
                            reduction_list_[r].attribute + "\"";
      try {
        require_attribute(particles, reduction_list_[r].attribute, w.key);
      } catch (const Error& e) {
        message = e.what();
      }
      log_error("step ", step, ": ", message, "; the condition is false (said once)");
    }
    return false;
  }
  return w.condition.holds(step, time);
}

}  // namespace voxspan
