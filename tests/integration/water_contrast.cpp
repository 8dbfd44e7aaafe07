#include "water_contrast.h"

#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <cstdint>

namespace voxspan::test {

std::vector<float> read_depth_exr(const std::filesystem::path& path, int& width, int& height) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  width = window.max.x - window.min.x + 1;
  height = window.max.y - window.min.y + 1;
  std::vector<float> z(std::size_t(width) * height, 0.0f);
  Imf::FrameBuffer frame;
  frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float),
                               sizeof(float) * std::size_t(width)));
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  return z;
}

Contrast water_contrast(const DecodedPng& png, const std::vector<float>& z) {
  const auto all = [&](int x, int y, bool hit) {
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int u = std::clamp(x + dx, 0, png.width - 1),
                  v = std::clamp(y + dy, 0, png.height - 1);
        if ((z[std::size_t(u) + std::size_t(v) * png.width] > 0) != hit) return false;
      }
    return true;
  };
  double tint_water = 0, tint_back = 0, lum = 0;
  Contrast c;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const std::uint8_t* p = &png.rgba[4 * (std::size_t(x) + std::size_t(y) * png.width)];
      const double tint = (double(p[2]) - double(p[0])) / 255;
      if (all(x, y, true)) {
        tint_water += tint;
        lum += (double(p[0]) + p[1] + p[2]) / (3 * 255.0);
        ++c.water;
      } else if (all(x, y, false)) {
        tint_back += tint;
        ++c.background;
        c.grey_background += std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) <= 10;
      }
    }
  if (c.water > 0 && c.background > 0) {
    c.tint = tint_water / c.water - tint_back / c.background;
    c.luminance = lum / c.water;
  }
  return c;
}

}  // namespace voxspan::test
