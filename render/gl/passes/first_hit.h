// render/gl/passes/first_hit.h - per pixel, the distance from the eye to where its ray first
// enters the fluid: the first span's entry depth times the ray's length per unit depth
// (render/README.md, "The span image"), along the unit ray through the pixel centre, row 0 at
// the top; 0 where the ray meets no fluid. What depth images (OpenEXR Z) are made of, with the
// span image's own depths; with the filtered ones (GpuSurfaces::depths), the shaded surface's.
// Reads: the span image's pixels, per-span (entry, exit) depths. Writes: a GpuFloatImage, the
// distance in r (g, b, a zero).
// Cost: one thread per pixel, 24 bytes read and 16 written each.
#pragma once

#include "render/gl/gpu_float_image.h"
#include "render/gl/gpu_span_image.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"

namespace voxspan {

class FirstHitPass {
 public:
  explicit FirstHitPass(const gl::ShaderLibrary& shaders);
  // `depths`: the image's own (GpuSpanImage::spans) or the filtered ones, per span.
  void run(const GpuSpanImage& image, const gl::Buffer& depths, GpuFloatImage& out);

 private:
  gl::Program program_;
};

}  // namespace voxspan
