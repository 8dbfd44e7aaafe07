#include "render/gl/passes/cut_at_walls.h"

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {
enum Binding : GLuint { kBackdropIn = binding::kSpanImageEnd };
}  // namespace

CutAtWallsPass::CutAtWallsPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute(
          "render/gl/passes/cut_at_walls.comp",
          binding::span_image_defines() + gl::defines({{"BACKDROP_BINDING", kBackdropIn}}))) {}

void CutAtWallsPass::run(const GpuSpanImage& image, const gl::Buffer& backdrop) {
  image.bind();
  backdrop.bind(GL_SHADER_STORAGE_BUFFER, kBackdropIn);
  set_grid_uniforms(program_, image.grid());
  dispatch_threads(program_, std::size_t(image.width()) * std::size_t(image.height()));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace voxspan
