#include "render/float_image.h"

#include <algorithm>

namespace voxspan {

void GpuFloatImage::resize(int width, int height) {
  width_ = width;
  height_ = height;
  buffer_.reserve(std::max<std::size_t>(16, std::size_t(width) * std::size_t(height) * 16));
}

FloatImage GpuFloatImage::download() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  FloatImage image(width_, height_);
  if (!image.rgba.empty()) buffer_.download(image.rgba.data(), image.rgba.size() * sizeof(float));
  return image;
}

}  // namespace voxspan
