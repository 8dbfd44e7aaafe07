#include "render_fixture.h"

#include "render/gl/pass_timer.h"

namespace voxspan::test {

Voxelizer& voxelizer() {
  static Voxelizer v(shaders());
  return v;
}

SpanImage voxelize(const Camera& camera, std::span<const ParticleSphere> particles,
                   const VoxelizeOptions& options, const CellStatesView& cells, FrameStats* stats) {
  gl::PassTimer timer(context().has_gpu_timers());
  FrameStats local;
  FrameStats& s = stats != nullptr ? *stats : local;
  const SpanImage image = voxelizer().run(camera, particles, cells, options, timer, s).download();
  timer.collect(s);
  return image;
}

}  // namespace voxspan::test
