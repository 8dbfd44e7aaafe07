// The picture as 8-bit sRGB on the GPU (render/gl/passes/srgb8_pack.h): bit for bit the bytes the
// host's linear_to_srgb8 makes of the float picture, at every kind of value (each step of the
// encode's table and both sides of its rounding edges, out of range, NaN, infinities). Through
// the renderer: tests/render/gl/test_picture_readback.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "render/gl/gpu_float_image.h"
#include "render/gl/passes/srgb8_pack.h"
#include "render/srgb8_image.h"
#include "tests/render/gl/shading_fixture.h"

namespace voxspan {
namespace {

// Values that find a different rounding: every table step's middle (where the index rounds)
// and its float neighbours, alpha's half steps and theirs, the ends and beyond.
std::vector<float> probe_values() {
  std::vector<float> v;
  const auto around = [&v](float x) {
    v.push_back(std::nextafter(x, -1.0f));
    v.push_back(x);
    v.push_back(std::nextafter(x, 2.0f));
  };
  const float steps = float(1 << kSrgb8TableBits);
  for (int i = 0; i < (1 << kSrgb8TableBits); ++i) around((float(i) + 0.5f) / steps);
  for (int i = 0; i < 255; ++i) around((float(i) + 0.5f) / 255.0f);
  const float inf = std::numeric_limits<float>::infinity();
  for (float x :
       {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, 1e-30f, -inf, inf, std::numeric_limits<float>::quiet_NaN()})
    v.push_back(x);
  return v;
}

// The values in every channel: a picture of width 256, the last row filled with zeros.
FloatImage picture_of(const std::vector<float>& values) {
  const int width = 256, height = int((values.size() + width - 1) / width);
  FloatImage image(width, height);
  for (std::size_t i = 0; i < values.size(); ++i)
    for (std::size_t c = 0; c < 4; ++c)
      image.rgba[i * 4 + c] = values[(i + c * 7919) % values.size()];
  return image;
}

TEST(Srgb8Pack, GivesTheHostsBytesBitForBit) {
  test::context();
  const FloatImage picture = picture_of(probe_values());
  GpuFloatImage image;
  image.upload(picture);
  Srgb8PackPass pack(test::shaders());
  gl::Buffer packed;
  pack.run(image, packed);
  std::vector<std::uint8_t> got(picture.rgba.size());
  packed.download(got.data(), got.size());
  const ImageRGBA8 want = linear_to_srgb8(picture.rgba, picture.width, picture.height);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
    if (got[i] != want.pixels[i] && ++differ <= 5)
      ADD_FAILURE() << "channel " << i % 4 << " of " << picture.rgba[i] << ": GPU " << int(got[i])
                    << ", host " << int(want.pixels[i]);
  EXPECT_EQ(differ, 0u) << "of " << got.size() << " channels";
}

}  // namespace
}  // namespace voxspan
