#include "render/volume_renderer.h"

#include "render/stat_names.h"

namespace voxspan {

void record(const VolumeCounts& c, Recorder& recorder) {
  recorder.count(counter::volume_particles, c.particles);
  recorder.count(counter::volume_particles_invalid, c.particles_invalid);
  recorder.count(counter::volume_particles_culled, c.particles_culled);
  recorder.count(counter::volume_samples, c.samples);
  recorder.count(counter::volume_kernel_evaluations, c.kernel_evaluations);
  recorder.count(counter::volume_rays_stopped, c.rays_stopped);
  recorder.count(counter::volume_iso_hits, c.iso_hits);
  recorder.count(counter::volume_iso_hits_unlit, c.iso_hits_unlit);
}

}  // namespace voxspan
