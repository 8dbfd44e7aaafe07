// tools/peers/vdb_level_set.h - the OpenVDB path a user would take instead of ours: the particles
// rasterized as spheres into a narrow-band level set (openvdb::tools::ParticlesToLevelSet),
// optionally smoothed (tools::LevelSetFilter, mean value: what Houdini's VDB Smooth SDF does by
// default), then one ray per pixel through the level set with its ray intersector
// (tools::LevelSetRayIntersector), first hit and, hit after hit, the length inside.
//
// ParticlesToLevelSet leaves out spheres smaller than its minimum radius, 1.5 voxels unless set:
// at a voxel of the particle radius it draws nothing at all. `min_radius_voxels` sets it; the
// particles it left out are counted in the note, never silently.
#pragma once

#include <vector>

#include "peer_surface.h"
#include "render/camera.h"

namespace voxspan::tools {

struct VdbLevelSetOptions {
  double voxel = 0;                // world units
  double half_width = 3;           // narrow band, voxels (OpenVDB's LEVEL_SET_HALF_WIDTH)
  double min_radius_voxels = 1.5;  // ParticlesToLevelSet::setRmin
  int smoothing = 0;               // mean-value filter iterations (width 1); 0: none
};

// x, y, z: particle centres (all of them, as a user passes them); every sphere `radius`.
PeerSurface vdb_level_set_surface(const std::vector<float>& x, const std::vector<float>& y,
                                  const std::vector<float>& z, double radius, const Camera& camera,
                                  const VdbLevelSetOptions& options);

}  // namespace voxspan::tools
