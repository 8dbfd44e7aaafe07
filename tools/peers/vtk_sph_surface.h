// tools/peers/vtk_sph_surface.h - the surface a VTK user would extract from the same particles,
// for the peer benchmark: vtkSPHInterpolator onto a volume, vtkFlyingEdges3D at an iso value of
// the interpolated volume fraction, and the mesh ray cast on the CPU with Embree to the same
// camera (render/camera.h) as our renderer's.
#pragma once

#include <vector>

#include "peer_surface.h"
#include "render/camera.h"

namespace voxspan::tools {

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
