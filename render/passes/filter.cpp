#include "render/passes/filter.h"

#include <algorithm>
#include <cmath>

#include "render/bindings.h"
#include "render/grid_uniforms.h"
#include "render/passes/dispatch.h"

namespace voxspan {
namespace {

// filter.comp's own buffer, after the surface data.
enum Binding : GLuint { kFilteredDepths = binding::kSurfacesEnd };

}  // namespace

// 2 (radius / pixel(z))^2 = scale / z^2, pixel(z) = 2 tan(fov_y / 2) / height * z.
double FilterPass::iteration_scale(const PerspectiveGrid& grid, double radius) {
  const double pixel_at_unit_depth = 2 * grid.view().tan_half_y / grid.height();
  const double r = radius / pixel_at_unit_depth;
  return 2 * r * r;
}

int FilterPass::iterations(const PerspectiveGrid& grid, const SurfaceOptions& options) {
  if (options.filter_radius <= 0 || options.max_iterations == 0) return 0;
  // The nearest surface needs the most iterations.
  return static_cast<int>(std::min<double>(
      options.max_iterations, iterations_at(grid, options.filter_radius, grid.near())));
}

FilterPass::FilterPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute("render/passes/filter.comp",
                               binding::surface_defines() +
                                   gl::defines({{"FILTERED_DEPTHS_BINDING", kFilteredDepths}}))) {}

double FilterPass::iterations_at(const PerspectiveGrid& grid, double radius, double depth) {
  return std::ceil(iteration_scale(grid, radius) / (depth * depth));
}

int FilterPass::run(const GpuSpanImage& image, GpuSurfaces& surfaces,
                    const SurfaceOptions& options) {
  validate(options);
  surfaces.set_filtered(-1);
  const std::size_t spans = image.span_count();
  const int iterations = spans == 0 ? 0 : FilterPass::iterations(image.grid(), options);
  if (iterations <= 0) return 0;
  for (int i = 0; i < 2; ++i) surfaces.filter_buffer(i).reserve(spans * 8);
  // Pass 0 reads the span depths; then the buffers alternate.
  set_grid_uniforms(program_, image.grid());
  program_.set("u_max_iterations", static_cast<unsigned>(options.max_iterations));
  program_.set("u_radius", float(options.filter_radius));
  program_.set("u_iteration_scale", float(iteration_scale(image.grid(), options.filter_radius)));
  for (int i = 0; i < kPasses; ++i) {
    surfaces.bind(image);
    surfaces.filter_buffer(i % 2).bind(GL_SHADER_STORAGE_BUFFER, kFilteredDepths);
    program_.set("u_filter_pass", static_cast<unsigned>(i));
    dispatch_threads(program_, spans);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    surfaces.set_filtered(i % 2);
  }
  return iterations;
}

}  // namespace voxspan
