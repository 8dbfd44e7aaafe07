#include "render/gl/passes/connect.h"

#include <string>

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {

constexpr const char* kShader = "render/gl/passes/connect.comp";

// connect.comp's own buffer, after the surface data.
enum Binding : GLuint { kTally = binding::kSurfacesEnd };

std::string binding_defines() {
  return binding::surface_defines() + gl::defines({{"TALLY_BINDING", kTally}});
}

}  // namespace

ConnectPass::ConnectPass(const gl::ShaderLibrary& shaders)
    : owners_(shaders.compute(kShader, binding_defines() + "#define CONNECT_OWNERS 1")),
      connect_(shaders.compute(kShader, binding_defines())),
      tally_(16) {}

std::uint32_t ConnectPass::run(const GpuSpanImage& image, GpuSurfaces& surfaces, double fold_step) {
  surfaces.prepare(image);
  if (image.span_count() == 0) return 0;
  tally_.clear();
  surfaces.bind(image);
  tally_.bind(GL_SHADER_STORAGE_BUFFER, kTally);
  set_grid_uniforms(owners_, image.grid());
  dispatch_threads(owners_, std::size_t(image.width()) * std::size_t(image.height()));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  set_grid_uniforms(connect_, image.grid());
  connect_.set("u_fold_step", float(fold_step));
  dispatch_threads(connect_, image.span_count());
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  return tally_.read_array<std::uint32_t, 1>()[0];
}

}  // namespace voxspan
