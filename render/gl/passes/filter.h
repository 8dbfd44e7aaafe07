// render/gl/passes/filter.h - the surface filter ([ZD15] sec. 3.4, 4.6;
// render/gl/passes/filter.comp): the smoothing of reciprocal depth along the surface links that n
// iterations of the 3x3 binomial kernel give, in four dispatches (rows, columns, rows again,
// the bounds: render/model/surface_filter.glsl), ping-ponging two depth buffers. The n of a
// point follows its depth so the filter's world radius stays constant (the rule:
// render/surface_passes.h).
// Reads: the span image, GpuSurfaces owners and links. Writes: GpuSurfaces filter buffers and
// marks the result as the surface depths.
// Cost: one thread per span and pass, reading up to 8 sqrt(m / 2) linked neighbours' depths per
// end in a pass of m iterations (n = 32: 24 + 32 + 24 reads, against 8 in each of 32
// iterations). n: max over the image of n(near), capped (the paper's GTX 970: 14 ms at 1080p
// for up to 20 iterations).
#pragma once

#include "render/gl/gpu_span_image.h"
#include "render/gl/gpu_surfaces.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"
#include "render/shade_options.h"
#include "render/surface_passes.h"

namespace voxspan {

class FilterPass {
 public:
  explicit FilterPass(const gl::ShaderLibrary& shaders);
  // Runs after ConnectPass, as `iterations` of the kernel (filter_iterations(),
  // render/surface_passes.h); 0: no filter, the span image's depths stay the surface depths.
  void run(const GpuSpanImage& image, GpuSurfaces& surfaces, const SurfaceOptions& options,
           int iterations);

 private:
  gl::Program program_;
};

}  // namespace voxspan
