// insitu/views/slice_view.h - views[i] of kind `slice`: a particle quantity interpolated with
// the SPH kernel on a plane at any position and orientation (insitu/views/sph_slice.h), drawn
// as its own 2D image through a colour map (insitu/views/color_map.h), with isolines and a
// colour bar at the right edge. Its settings, for the code that reads them by type.
//
// Reads: every owned particle the solver passes (positions, the quantity, mass and density),
// the fluid's box (the automatic plane origin and extent). Writes: the picture. Runs on the
// CPU whichever renderer draws the surfaces. In an MPI job every rank sums its owned
// particles' part and rank 0 draws the sum of all (exact).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "insitu/config/settings.h"
#include "insitu/views/color_map.h"
#include "insitu/views/sph_slice.h"

namespace voxspan {

struct SlicePlaneConfig {
  std::optional<Vec3d> origin;  // nullopt = the centre of the fluid's box
  Vec3d normal{0, 1, 0};
  bool operator==(const SlicePlaneConfig&) const = default;
};

struct SliceSettings : CloneAs<SliceSettings, ViewSettings> {
  std::string quantity;  // the attribute interpolated (a vector: its magnitude)
  SphKernel kernel = SphKernel::cubic_spline;
  std::optional<double> smoothing_length;  // h, world units; nullopt = 1.3 spacings
  bool shepard = false;
  std::string mass = "mass", density = "density";
  SlicePlaneConfig plane;
  std::optional<double> extent;  // the plane's width, world units; nullopt = fit the fluid
  ColorMap color_map = ColorMap::viridis;
  std::optional<std::array<double, 2>> range;  // nullopt = the step's min and max
  int isolines = 8;
  bool operator==(const SliceSettings&) const = default;
};

// h = 1.3 spacings when the view does not say: PySPH's usual hdx.
inline constexpr double kAutoSmoothingFactor = 1.3;

}  // namespace voxspan
