#include "render/gl/passes/filter.h"

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {

// filter.comp's own buffer, after the surface data.
enum Binding : GLuint { kFilteredDepths = binding::kSurfacesEnd };

}  // namespace

FilterPass::FilterPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute("render/gl/passes/filter.comp",
                               binding::surface_defines() +
                                   gl::defines({{"FILTERED_DEPTHS_BINDING", kFilteredDepths}}))) {}

void FilterPass::run(const GpuSpanImage& image, GpuSurfaces& surfaces,
                     const SurfaceOptions& options, int iterations) {
  surfaces.set_filtered(-1);
  const std::size_t spans = image.span_count();
  if (iterations <= 0 || spans == 0) return;
  for (int i = 0; i < 2; ++i) surfaces.filter_buffer(i).reserve(spans * 8);
  // Pass 0 reads the span depths; then the buffers alternate.
  set_grid_uniforms(program_, image.grid());
  program_.set("u_max_iterations",
               static_cast<unsigned>(filter_iteration_cap(image.grid(), options)));
  program_.set("u_radius", float(options.filter_radius));
  program_.set("u_iteration_scale",
               float(filter_iteration_scale(image.grid(), options.filter_radius)));
  for (int i = 0; i < kFilterPasses; ++i) {
    surfaces.bind(image);
    surfaces.filter_buffer(i % 2).bind(GL_SHADER_STORAGE_BUFFER, kFilteredDepths);
    program_.set("u_filter_pass", static_cast<unsigned>(i));
    dispatch_threads(program_, spans);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    surfaces.set_filtered(i % 2);
  }
}

}  // namespace voxspan
