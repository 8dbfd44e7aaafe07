// render/gl/passes/connect.h - surface connection ([ZD15] sec. 3.3, Listing 1;
// render/gl/passes/connect.comp, the rule in render/model/links.glsl).
// Reads: the span image. Writes: GpuSurfaces::owners() (each span's pixel) and links() (per
// span the entry's and the exit's word: one byte per neighbour pixel).
// Cost: one thread per pixel storing its pixel number per span, then one thread per span with
// two binary searches in each of the four neighbour columns; 12 bytes written per span (the
// paper's GTX 970: 1.2 ms at 1080p).
#pragma once

#include <cstdint>

#include "render/gl/gpu_span_image.h"
#include "render/gl/gpu_surfaces.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"

namespace voxspan {

class ConnectPass {
 public:
  explicit ConnectPass(const gl::ShaderLibrary& shaders);
  // Sizes `surfaces` for the image and links every span, not across folds deeper than
  // `fold_step` (SurfaceOptions). Returns the spans no link can name (past index 252 of their
  // pixel: neighbours see the surface end before them).
  std::uint32_t run(const GpuSpanImage& image, GpuSurfaces& surfaces, double fold_step);

 private:
  gl::Program owners_, connect_;
  gl::Buffer tally_;
};

}  // namespace voxspan
