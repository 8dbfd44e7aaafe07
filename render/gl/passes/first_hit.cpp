#include "render/gl/passes/first_hit.h"

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {
enum Binding : GLuint { kFirstHit = binding::kSpanImageEnd, kDepths };
}  // namespace

FirstHitPass::FirstHitPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute(
          "render/gl/passes/first_hit.comp",
          binding::span_image_defines() +
              gl::defines({{"FIRST_HIT_BINDING", kFirstHit}, {"DEPTHS_BINDING", kDepths}}))) {}

void FirstHitPass::run(const GpuSpanImage& image, const gl::Buffer& depths, GpuFloatImage& out) {
  out.resize(image.width(), image.height());
  image.bind();
  out.buffer().bind(GL_SHADER_STORAGE_BUFFER, kFirstHit);
  depths.bind(GL_SHADER_STORAGE_BUFFER, kDepths);
  set_grid_uniforms(program_, image.grid());
  dispatch_threads(program_, std::size_t(image.width()) * std::size_t(image.height()));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace voxspan
