// render/cpu/volume_renderer.h - the CPU volume renderer (render/cpu/volume_caster.h) behind the
// volume-renderer interface (render/volume_renderer.h), and the base both backends share.
#pragma once

#include <memory>

#include "render/cpu/volume_caster.h"
#include "render/volume_renderer.h"

namespace voxspan {

// An MPI frame's parts (its hulls, its part, the hits' field sums) through the CPU caster: the
// same on every backend, so a frame composites the same whichever renderer drew each rank.
class CasterPartsVolumeRenderer : public VolumeRenderer {
 public:
  VolumeCounts cover(const Camera& camera, std::span<const VolumeParticle> particles,
                     const VolumeOptions& options, Recorder& recorder,
                     std::vector<SampleRange>& hulls) override;
  VolumeCounts render_part(const PixelRanges& shared, Recorder& recorder, VolumePart& out) override;
  void field_sums(std::span<const HitQuery> queries, Recorder& recorder,
                  std::vector<FieldSums>& out) override;

 protected:
  VolumeCaster caster_;
};

std::unique_ptr<VolumeRenderer> make_cpu_volume_renderer();

}  // namespace voxspan
