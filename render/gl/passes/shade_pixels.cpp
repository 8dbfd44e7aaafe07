#include "render/gl/passes/shade_pixels.h"

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {

ShadePixelsPass::ShadePixelsPass(const gl::ShaderLibrary& shaders, std::string_view shader)
    : program_(shaders.compute(shader, binding::shade_defines())) {}

void ShadePixelsPass::run(const GpuSpanImage& image, const GpuSurfaces& surfaces,
                          const model::ShadeUniforms& uniforms, const gl::Buffer& backdrop,
                          GpuFloatImage& out) {
  out.resize(image.width(), image.height());
  surfaces.bind(image);
  out.buffer().bind(GL_SHADER_STORAGE_BUFFER, binding::kShadedImage);
  backdrop.bind(GL_SHADER_STORAGE_BUFFER, binding::kBackdrop);
  set_grid_uniforms(program_, image.grid());
  set_shade_uniforms(program_, uniforms);
  dispatch_threads(program_, std::size_t(image.width()) * std::size_t(image.height()));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace voxspan
