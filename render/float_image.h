// render/float_image.h - the shaded picture: linear RGBA floats per pixel, row 0 at the top,
// as the shading passes write it on the GPU (GpuFloatImage: a buffer of vec4, pixel
// x + y * width) and as tests compare it on the CPU (FloatImage). 8-bit sRGB PNG output is the
// runtime's (insitu/outputs/png_image.h: linear_to_srgb8 and write_png).
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "render/gl/objects.h"

namespace voxspan {

struct FloatImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4

  FloatImage() = default;
  FloatImage(int w, int h) : width(w), height(h), rgba(std::size_t(w) * std::size_t(h) * 4, 0.0f) {}
  glm::vec4 at(int x, int y) const {
    const float* p = &rgba[(std::size_t(x) + std::size_t(y) * std::size_t(width)) * 4];
    return {p[0], p[1], p[2], p[3]};
  }
  void set(int x, int y, glm::vec4 c) {
    float* p = &rgba[(std::size_t(x) + std::size_t(y) * std::size_t(width)) * 4];
    p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = c.a;
  }
};

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

 private:
  int width_ = 0, height_ = 0;
  gl::Buffer buffer_;
};

}  // namespace voxspan
