// render/volume_renderer.h - what a volume view asks of a renderer (render/volume.h says what a
// frame is), whichever one the process uses: made once by make_volume_renderer
// (render/backend.h). Implementations: render/cpu/volume_renderer.h (exact sums in double) and
// render/gl/volume_renderer.h (the march on the GPU, float sums).
#pragma once

#include <span>
#include <vector>

#include "render/camera.h"
#include "render/recorder.h"
#include "render/volume.h"
#include "render/volume_parts.h"

namespace voxspan {

class VolumeRenderer {
 public:
  virtual ~VolumeRenderer() = default;
  // One frame into `out` (its storage reused), timed as pass::volume and counted (volume.*:
  // render/stat_names.h). Throws voxspan::Error on bad options or camera; bad particles are
  // counted and skipped.
  virtual VolumeCounts render(const Camera& camera, std::span<const VolumeParticle> particles,
                              const VolumeOptions& options, Recorder& recorder,
                              VolumeFrame& out) = 0;

  // This rank's part of a frame over several MPI ranks (render/volume_parts.h; the view's
  // compositor, insitu/views/volume_compositor.h, calls them in this order): the hull of its
  // samples per pixel; its part given the samples others reach too; its sums at the merge's
  // iso hits (appended to `out`). Timed and counted as render() is, cover and part together.
  virtual VolumeCounts cover(const Camera& camera, std::span<const VolumeParticle> particles,
                             const VolumeOptions& options, Recorder& recorder,
                             std::vector<SampleRange>& hulls) = 0;
  virtual VolumeCounts render_part(const PixelRanges& shared, Recorder& recorder,
                                   VolumePart& out) = 0;
  virtual void field_sums(std::span<const HitQuery> queries, Recorder& recorder,
                          std::vector<FieldSums>& out) = 0;
};

// A frame's counts into the recorder, as every volume renderer reports them.
void record(const VolumeCounts& counts, Recorder& recorder);

}  // namespace voxspan
