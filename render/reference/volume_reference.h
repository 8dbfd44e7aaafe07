// render/reference/volume_reference.h - the exact reference of the volume views (render/volume.h):
// every pixel's ray tested against every particle's support (no binning), then at each sample
// of the lattice the sums over the particles whose supports hold it, in double and in the
// particles' own order, composited by the same model file as the renderers
// (render/model/volume.glsl) and lit from the gradient summed the same way. What the renderers'
// pictures are held to at their own samples; converged_volume() refines the samples until the
// picture stops changing, which is the volume rendering integral the sampling approximates.
// Rows in parallel (oneTBB); O(pixels x particles): for test scenes, not for production.
#pragma once

#include <span>

#include "render/camera.h"
#include "render/volume.h"

namespace voxspan {

VolumeCounts volume_reference(const Camera& camera, std::span<const VolumeParticle> particles,
                              const VolumeOptions& options, VolumeFrame& out);

// The field at a world point, from every particle, in double: its value where defined (some
// particle reaches it; with Shepard, w at least the floor).
struct FieldValue {
  double q = 0, w = 0;
  bool defined = false;
};
FieldValue volume_field(std::span<const VolumeParticle> particles, const VolumeOptions& options,
                        glm::dvec3 point);

// The reference with `sampling` doubled until no channel of any pixel changes by more than
// `tolerance` (at most `max_doublings` times; `doublings` gets how many it took).
VolumeFrame converged_volume(const Camera& camera, std::span<const VolumeParticle> particles,
                             const VolumeOptions& options, double tolerance, int max_doublings,
                             int* doublings = nullptr);

}  // namespace voxspan
