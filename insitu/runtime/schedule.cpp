#include "insitu/runtime/schedule.h"

#include <algorithm>

#include "insitu/runtime/registry.h"

namespace voxspan {

bool StepPlan::any() const {
  return render || std::find(outputs.begin(), outputs.end(), true) != outputs.end();
}

Schedule::Schedule(const Config& config)
    : render_(config.trigger), has_views_(!config.views.empty()) {
  for (const ConfiguredOutput& o : config.outputs) {
    const ViewNeeds needs = registered_output_kind(o.kind).needs;
    // An output of the views' products has nothing to write without views.
    const bool enabled = o.settings->enabled && (has_views_ || !needs.any());
    outputs_.push_back({Trigger(o.settings->trigger), enabled, needs.any()});
  }
}

StepPlan Schedule::blank() const { return {false, std::vector<bool>(outputs_.size(), false)}; }

void Schedule::plan(std::int64_t step, double time, bool last_step, StepPlan& plan) {
  bool render = has_views_ && render_.is_due(step, time, last_step);
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    Entry& o = outputs_[i];
    if (!o.enabled || !o.trigger.is_due(step, time, last_step)) continue;
    plan.outputs[i] = true;
    render = render || o.renders;
  }
  plan.render = plan.render || render;
}

StepPlan Schedule::plan(std::int64_t step, double time, bool last_step) {
  StepPlan p = blank();
  plan(step, time, last_step, p);
  return p;
}

}  // namespace voxspan
