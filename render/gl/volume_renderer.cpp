#include "render/gl/volume_renderer.h"

#include "render/cpu/volume_renderer.h"
#include "render/gl/passes/volume_march.h"
#include "render/stat_names.h"

namespace voxspan {
namespace {

// The caster's project, sort and bin, then the march on the GPU; an MPI frame's parts on the
// CPU (CasterPartsVolumeRenderer).
class GlVolumeRenderer final : public CasterPartsVolumeRenderer {
 public:
  explicit GlVolumeRenderer(const gl::ShaderLibrary& shaders) : march_(shaders) {}

  VolumeCounts render(const Camera& camera, std::span<const VolumeParticle> particles,
                      const VolumeOptions& options, Recorder& recorder, VolumeFrame& out) override {
    VolumeCounts counts;
    {
      auto t = recorder.host(pass::volume);
      counts = caster_.setup(camera, particles, options, setup_);
      VolumeCounts marched = counts;
      if (march_.run(camera, setup_, options, model::VolumeHost(options), out, marched)) {
        counts = marched;
      } else {  // past llvmpipe's loop budget: the CPU caster's frame
        counts = caster_.run(camera, particles, options, out);
        ++counts.gl_frames_on_cpu;
      }
    }
    record(counts, recorder);
    return counts;
  }

 private:
  VolumeSetup setup_;
  VolumeMarchPass march_;
};

}  // namespace

std::unique_ptr<VolumeRenderer> make_gl_volume_renderer(const gl::ShaderLibrary& shaders) {
  return std::make_unique<GlVolumeRenderer>(shaders);
}

}  // namespace voxspan
