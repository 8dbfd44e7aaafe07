#include "render/gl/passes/normals.h"

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {

NormalsPass::NormalsPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute("render/gl/passes/normals.comp", binding::surface_defines())) {}

void NormalsPass::run(const GpuSpanImage& image, const GpuSurfaces& surfaces,
                      const gl::Buffer& backdrop, bool walls, double fold_step) {
  if (image.span_count() == 0) return;
  surfaces.bind(image);
  backdrop.bind(GL_SHADER_STORAGE_BUFFER, binding::kWallDepths);
  program_.set("u_walls_cut", walls ? 1 : 0);
  program_.set("u_fold_step", float(fold_step));
  set_grid_uniforms(program_, image.grid());
  dispatch_threads(program_, image.span_count());
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace voxspan
