// render/gl/gpu_float_image.h - the shaded picture (render/float_image.h) as the shading passes
// write it on the GPU: a buffer of vec4, pixel x + y * width, row 0 at the top.
#pragma once

#include "render/float_image.h"
#include "render/gl/objects.h"

namespace voxspan {

class GpuFloatImage {
 public:
  // Sizes the buffer for width x height pixels (grows only).
  void resize(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  const gl::Buffer& buffer() const { return buffer_; }
  FloatImage download() const;
  // Into `out`, reusing its storage (no allocation once it has held an image this size).
  void download(FloatImage& out) const;
  // `image` to the GPU, sized to it (a picture made on the host: tests, tools).
  void upload(const FloatImage& image);

 private:
  int width_ = 0, height_ = 0;
  gl::Buffer buffer_;
};

}  // namespace voxspan
