// insitu/schedule.h - which work a step needs, from the triggers of the config: the render
// trigger and each enabled output's own trigger. plan() is what the adapter calls first every
// step; when nothing is due it returns after a handful of compares (docs/benchmarks.md,
// "Runtime").
#pragma once

#include <cstdint>

#include "insitu/config.h"
#include "insitu/trigger.h"

namespace voxspan {

struct StepPlan {
  bool render = false;  // classify, voxelize and shade every view
  bool png = false;     // write each rendered view as PNG (implies render)
  bool stats = false;   // append the step's stats line
  bool vdb = false;     // write an OpenVDB snapshot
  bool vtk = false;     // write the VTK files (and update the .pvd series)

  bool any() const { return render || png || stats || vdb || vtk; }
  // The cell classification and boundary compaction feed rendering and both snapshot kinds.
  bool needs_classification() const { return render || vdb || vtk; }
};

class Schedule {
 public:
  explicit Schedule(const Config& config);

  // Once per solver step, steps non-decreasing; last_step when the solver says it is its last.
  StepPlan plan(std::int64_t step, double time, bool last_step = false) {
    StepPlan p;
    p.png = png_enabled_ && png_.is_due(step, time, last_step);
    p.render = has_views_ && (render_.is_due(step, time, last_step) || p.png);
    p.stats = stats_enabled_ && stats_.is_due(step, time, last_step);
    p.vdb = vdb_enabled_ && vdb_.is_due(step, time, last_step);
    p.vtk = vtk_enabled_ && vtk_.is_due(step, time, last_step);
    return p;
  }

 private:
  Trigger render_, png_, stats_, vdb_, vtk_;
  bool has_views_, png_enabled_, stats_enabled_, vdb_enabled_, vtk_enabled_;
};

}  // namespace voxspan
