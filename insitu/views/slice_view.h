// insitu/views/slice_view.h - views[i] of kind `slice`: a particle quantity interpolated with
// the SPH kernel on a plane at any position and orientation (insitu/views/sph_slice.h), drawn
// as its own 2D image through a colour map (insitu/views/color_map.h), with isolines, a colour
// bar at the right edge and axes in world units (insitu/views/slice_layer.h). Its settings, for
// the code that reads them by type.
//
// Reads: every owned particle the solver passes (positions, the quantity, mass and density),
// the fluid's box (the automatic plane origin and extent). Writes: the picture. Runs on the
// CPU whichever renderer draws the surfaces. In an MPI job every rank sums its owned
// particles' part and rank 0 draws the sum of all (exact).
#pragma once

#include "insitu/config/settings.h"
#include "insitu/views/slice_layer.h"

namespace voxspan {

struct SliceSettings : CloneAs<SliceSettings, ViewSettings>, SliceField {
  bool operator==(const SliceSettings&) const = default;
};

}  // namespace voxspan
