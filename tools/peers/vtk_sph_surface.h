// tools/peers/vtk_sph_surface.h - the surface a VTK user would extract from the same particles,
// for the peer benchmark: vtkSPHInterpolator onto a volume, vtkFlyingEdges3D at an iso value of
// the interpolated volume fraction, and the mesh ray cast on the CPU with Embree to the same
// camera (render/camera.h) as our renderer's.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "render/camera.h"

namespace voxspan::tools {

// A peer's surface seen from a camera: per pixel (row-major, row 0 at the top, as
// ViewFrame::world_ray(x, y) casts) the distance from the eye along the unit ray to the first
// hit (+infinity: none), and the time of each stage in ms.
struct PeerSurface {
  std::vector<float> first_hit;
  // Total length of the ray inside the surface (0: none), from all mesh hits along the ray,
  // paired into entering/leaving by the side of the triangle each hit is on.
  std::vector<float> thickness;
  std::map<std::string, double> ms;  // "interpolate", "contour", "bvh", "cast", "total"
  std::size_t triangles = 0;
  std::string settings;  // a short text of the settings, for the benchmark's table
};

struct VtkSphOptions {
  double voxel = 0;             // volume spacing (world)
  double smoothing_length = 0;  // SPH h (world); cubic spline (vtkSPHCubicKernel) unless quintic
  bool quintic = false;
  double iso = 0.5;  // contour of the interpolated volume fraction
};

// x, y, z: the fluid particles' centres; spacing: their rest spacing (each particle's volume is
// spacing^3, so that the interpolated fraction Sum_j V_j W(r - r_j, h) is ~1 inside the fluid and
// 0 outside). Every call runs the whole pipeline afresh (the times are one frame's; the caller
// takes medians). Throws voxspan::Error on bad input.
PeerSurface vtk_sph_surface(const std::vector<float>& x, const std::vector<float>& y,
                            const std::vector<float>& z, double spacing, const Camera& camera,
                            const VtkSphOptions& options);

}  // namespace voxspan::tools
