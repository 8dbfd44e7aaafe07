// The kinds, each defined in its own file; a new view or output kind is one line here.
#include "insitu/runtime/registry.h"

#include "voxspan/error.h"

namespace voxspan {

ViewKind surface_view_kind();    // insitu/views/surface_view.cpp
ViewKind slice_view_kind();      // insitu/views/slice_view.cpp
ViewKind particles_view_kind();  // insitu/views/particles_view.cpp
ViewKind volume_view_kind();     // insitu/views/volume_view.cpp

OutputKind png_output_kind();     // insitu/outputs/kinds/png_output.cpp
OutputKind vdb_output_kind();     // insitu/outputs/kinds/vdb_output.cpp
OutputKind mesh_output_kind();    // insitu/outputs/kinds/mesh_output.cpp
OutputKind vtk_output_kind();     // insitu/outputs/kinds/vtk_output.cpp
OutputKind depth_output_kind();   // insitu/outputs/kinds/depth_output.cpp
OutputKind exr_output_kind();     // insitu/outputs/kinds/exr_output.cpp
OutputKind stats_output_kind();   // insitu/outputs/kinds/stats_output.cpp
OutputKind cinema_output_kind();  // insitu/outputs/kinds/cinema_output.cpp

namespace {

Kinds make_kinds() {
  Kinds k;
  k.views = {surface_view_kind(), slice_view_kind(), particles_view_kind(), volume_view_kind()};
  // Stats last: its line reports the time the other outputs took on the step.
  k.outputs = {png_output_kind(),   vdb_output_kind(), mesh_output_kind(),   vtk_output_kind(),
               depth_output_kind(), exr_output_kind(), cinema_output_kind(), stats_output_kind()};
  for (const ViewKind& v : k.views) k.config.views.push_back(v.config);
  for (const OutputKind& o : k.outputs) k.config.outputs.push_back(o.config);
  return k;
}

}  // namespace

const Kinds& registered_kinds() {
  static const Kinds kinds = make_kinds();
  return kinds;
}

const ViewKind& registered_view_kind(std::string_view name) {
  for (const ViewKind& k : registered_kinds().views)
    if (k.config.name == name) return k;
  throw make_error("no view kind \"", name, "\"");
}

const OutputKind& registered_output_kind(std::string_view name) {
  for (const OutputKind& k : registered_kinds().outputs)
    if (k.config.name == name) return k;
  throw make_error("no output kind \"", name, "\"");
}

}  // namespace voxspan
