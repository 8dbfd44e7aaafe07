// render/float_image.h - the shaded picture in host memory: linear RGBA floats per pixel, row 0
// at the top (the GL renderer's on the GPU: render/gl/gpu_float_image.h). 8-bit sRGB PNG output
// is the runtime's (insitu/outputs/formats/png_image.h: linear_to_srgb8 and write_png).
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

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

}  // namespace voxspan
