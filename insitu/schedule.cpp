#include "insitu/schedule.h"

namespace voxspan {

Schedule::Schedule(const Config& config)
    : render_(config.trigger),
      png_(config.outputs.png.trigger),
      stats_(config.outputs.stats.trigger),
      vdb_(config.outputs.vdb.trigger),
      vtk_(config.outputs.vtk.trigger),
      has_views_(!config.views.empty()),
      png_enabled_(config.outputs.png.enabled && !config.views.empty()),
      stats_enabled_(config.outputs.stats.enabled),
      vdb_enabled_(config.outputs.vdb.enabled),
      vtk_enabled_(config.outputs.vtk.enabled) {}

}  // namespace voxspan
