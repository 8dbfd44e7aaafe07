#include "render/gl/passes/deep_ao.h"

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {

DeepAoPass::DeepAoPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute("render/gl/passes/deep_ao.comp", binding::surface_defines())) {}

void DeepAoPass::run(const GpuSpanImage& image, const GpuSurfaces& surfaces,
                     const model::ShadeUniforms& uniforms) {
  surfaces.bind(image);
  set_grid_uniforms(program_, image.grid());
  set_shade_uniforms(program_, uniforms);
  dispatch_threads(program_, std::size_t(image.width()) * std::size_t(image.height()));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace voxspan
