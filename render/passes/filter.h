// render/passes/filter.h - the surface filter ([ZD15] sec. 3.4, 4.6;
// render/passes/filter.comp): the smoothing of reciprocal depth along the surface links that n
// iterations of the 3x3 binomial kernel give, in four dispatches (rows, columns, rows again,
// the bounds: render/model/surface_filter.glsl), ping-ponging two depth buffers. The n of a
// point follows its depth so the filter's world radius stays constant (SurfaceOptions in
// render/shade_options.h says how).
// Reads: the span image, GpuSurfaces owners and links. Writes: GpuSurfaces filter buffers and
// marks the result as the surface depths.
// Cost: one thread per span and pass, reading up to 8 sqrt(m / 2) linked neighbours' depths per
// end in a pass of m iterations (n = 32: 24 + 32 + 24 reads, against 8 in each of 32
// iterations). n: max over the image of n(near), capped (the paper's GTX 970: 14 ms at 1080p
// for up to 20 iterations).
#pragma once

#include "render/gl/objects.h"
#include "render/gl/shader_library.h"
#include "render/gpu_span_image.h"
#include "render/gpu_surfaces.h"
#include "render/shade_options.h"

namespace voxspan {

class FilterPass {
 public:
  static constexpr int kPasses = 4;  // render/model/surface_filter.glsl's

  explicit FilterPass(const gl::ShaderLibrary& shaders);
  // Runs after ConnectPass. Returns the iterations the passes stand for (0: filter off or
  // nothing to do; the span image's depths stay the surface depths).
  int run(const GpuSpanImage& image, GpuSurfaces& surfaces, const SurfaceOptions& options);

  // Iterations a point at `depth` gets (before the cap): ceil(2 (radius / pixel(depth))^2).
  static double iterations_at(const PerspectiveGrid& grid, double radius, double depth);
  // The `scale` of n(z) = ceil(scale / z^2) (render/model/surface_filter.glsl).
  static double iteration_scale(const PerspectiveGrid& grid, double radius);
  // The iterations a frame stands for: those of its nearest depth, capped; 0 with the filter
  // off.
  static int iterations(const PerspectiveGrid& grid, const SurfaceOptions& options);

 private:
  gl::Program program_;
};

}  // namespace voxspan
