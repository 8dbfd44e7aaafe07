#include "render/gl/gpu_float_image.h"

#include <algorithm>

namespace voxspan {

void GpuFloatImage::resize(int width, int height) {
  width_ = width;
  height_ = height;
  buffer_.reserve(std::max<std::size_t>(16, std::size_t(width) * std::size_t(height) * 16));
}

FloatImage GpuFloatImage::download() const {
  FloatImage image;
  download(image);
  return image;
}

void GpuFloatImage::download(FloatImage& out) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the shade pass wrote it in a shader
  out.width = width_;
  out.height = height_;
  out.rgba.resize(std::size_t(width_) * std::size_t(height_) * 4);
  if (!out.rgba.empty()) buffer_.download(out.rgba.data(), out.rgba.size() * sizeof(float));
}

void GpuFloatImage::upload(const FloatImage& image) {
  resize(image.width, image.height);
  if (!image.rgba.empty()) buffer_.upload(image.rgba.data(), image.rgba.size() * sizeof(float));
}

}  // namespace voxspan
