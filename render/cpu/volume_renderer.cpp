#include "render/cpu/volume_renderer.h"

#include "render/cpu/volume_caster.h"
#include "render/stat_names.h"

namespace voxspan {
namespace {

class CpuVolumeRenderer final : public VolumeRenderer {
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

 private:
  VolumeCaster caster_;
};

}  // namespace

std::unique_ptr<VolumeRenderer> make_cpu_volume_renderer() {
  return std::make_unique<CpuVolumeRenderer>();
}

}  // namespace voxspan
