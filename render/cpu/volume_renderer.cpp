#include "render/cpu/volume_renderer.h"

#include "render/stat_names.h"

namespace voxspan {

VolumeCounts CasterPartsVolumeRenderer::cover(const Camera& camera,
                                              std::span<const VolumeParticle> particles,
                                              const VolumeOptions& options, Recorder& recorder,
                                              std::vector<SampleRange>& hulls) {
  auto t = recorder.host(pass::volume);
  return caster_.cover(camera, particles, options, hulls);
}

VolumeCounts CasterPartsVolumeRenderer::render_part(const PixelRanges& shared, Recorder& recorder,
                                                    VolumePart& out) {
  auto t = recorder.host(pass::volume);
  return caster_.run_part(shared, out);
}

void CasterPartsVolumeRenderer::field_sums(std::span<const HitQuery> queries, Recorder& recorder,
                                           std::vector<FieldSums>& out) {
  auto t = recorder.host(pass::volume);
  caster_.field_sums(queries, out);
}

namespace {

class CpuVolumeRenderer final : public CasterPartsVolumeRenderer {
 public:
  VolumeCounts render(const Camera& camera, std::span<const VolumeParticle> particles,
                      const VolumeOptions& options, Recorder& recorder, VolumeFrame& out) override {
    VolumeCounts counts;
    {
      auto t = recorder.host(pass::volume);
      counts = caster_.run(camera, particles, options, out);
    }
    record(counts, recorder);
    return counts;
  }
};

}  // namespace

std::unique_ptr<VolumeRenderer> make_cpu_volume_renderer() {
  return std::make_unique<CpuVolumeRenderer>();
}

}  // namespace voxspan
