// render/gl/passes/srgb8_pack.h - the shaded picture as 8-bit sRGB on the GPU, so that a picture
// only PNG files and the live page take is read back at 4 bytes a pixel instead of 16.
// Reads: a GpuFloatImage (linear RGBA) and the encode's table (render/srgb8_image.h: the host's
// linear_to_srgb8 reads the same table the same way, so both give the same bytes). Writes: one
// uint a pixel, R in the low byte then G, B, A (ImageRGBA8's bytes on a little-endian host),
// pixel x + y * width, row 0 at the top.
// Cost: one thread per pixel, 16 bytes read (and a table entry a channel) and 4 written each.
#pragma once

#include "render/gl/gpu_float_image.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"

namespace voxspan {

class Srgb8PackPass {
 public:
  explicit Srgb8PackPass(const gl::ShaderLibrary& shaders);  // uploads the table (64 KiB)
  // `image` packed into `out` (grown to 4 bytes a pixel when smaller); its writes made visible
  // to a buffer copy and to shaders.
  void run(const GpuFloatImage& image, gl::Buffer& out) const;

 private:
  gl::Program program_;
  gl::Buffer table_;
};

}  // namespace voxspan
