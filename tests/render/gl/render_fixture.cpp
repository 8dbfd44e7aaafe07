#include "tests/render/gl/render_fixture.h"

#include "render/gl/gpu_recorder.h"

namespace voxspan::test {

Voxelizer& voxelizer() {
  static Voxelizer v(shaders());
  return v;
}

SpanImage voxelize(const Camera& camera, std::span<const ParticleSphere> particles,
                   const VoxelizeOptions& options, const CellStatesView& cells, FrameStats* stats) {
  FrameStats local;
  gl::GpuRecorder recorder(stats != nullptr ? *stats : local, context().has_gpu_timers());
  const SpanImage image = voxelizer().run(camera, particles, cells, options, recorder).download();
  recorder.collect();
  return image;
}

}  // namespace voxspan::test
