// outputs.exr's deep image (insitu/outputs/exr_image.h), read back with OpenEXR's own deep
// reader: per pixel as many samples as the span image stores, Z and ZBack the spans' entry
// and exit depths times the pixel ray's length (distances along the unit ray), to float
// precision; pixels without spans have no samples. And its RGBA companion.
#include <gtest/gtest.h>

#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfPartType.h>

#include <cmath>
#include <fstream>
#include <vector>

#include "deep_exr_reader.h"
#include "insitu/outputs/exr_image.h"
#include "temp_folder.h"

namespace voxspan {
namespace {

// 7 x 5 pixels, pixel (x, y) holding (x + y) % 3 spans at depths that differ from pixel to pixel.
SpanImage test_spans() {
  Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.width = 7;
  camera.height = 5;
  SpanImage image;
  image.grid = PerspectiveGrid::over(camera, 0.5, 10, GridOptions{});
  image.pixels.resize(35);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      PixelSpans& p = image.pixels[std::size_t(x) + 7 * std::size_t(y)];
      p.offset = std::uint32_t(image.spans.size());
      p.count = p.total = std::uint32_t((x + y) % 3);
      for (std::uint32_t k = 0; k < p.count; ++k) {
        const float entry = 1.0f + 0.37f * float(x) + 0.11f * float(y) + 2.0f * float(k);
        image.spans.push_back({entry, entry + 0.5f + 0.01f * float(x)});
      }
    }
  return image;
}

void write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(DeepExr, ReadBackGivesTheSpansAsDistancesAlongTheUnitRay) {
  test::TempFolder dir;
  const SpanImage spans = test_spans();
  write(dir / "deep.exr", encode_deep_exr(spans));

  const test::DeepExr d = test::read_deep_exr(dir / "deep.exr");
  EXPECT_EQ(d.type, Imf::DEEPSCANLINE);
  ASSERT_EQ(d.width, 7);
  ASSERT_EQ(d.height, 5);
  EXPECT_TRUE(d.has_z);
  EXPECT_TRUE(d.has_z_back);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      const std::size_t p = std::size_t(x) + 7 * std::size_t(y);
      ASSERT_EQ(d.z[p].size(), spans.pixels[p].count) << x << "," << y;
      const double scale = spans.grid.view().ray_scale(x, y);
      for (std::uint32_t k = 0; k < spans.pixels[p].count; ++k) {
        const Span& s = spans.spans[spans.pixels[p].offset + k];
        EXPECT_FLOAT_EQ(d.z[p][k], float(s.entry * scale)) << x << "," << y << " span " << k;
        EXPECT_FLOAT_EQ(d.z_back[p][k], float(s.exit * scale)) << x << "," << y << " span " << k;
      }
    }
}

TEST(DeepExr, TheColourCompanionHoldsThePictureAsRgbaFloats) {
  test::TempFolder dir;
  FloatImage picture(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) picture.set(x, y, {0.1f * x, 0.2f * y, 0.5f, 1.0f});
  write(dir / "color.exr", encode_exr_rgba(picture));
  Imf::InputFile file((dir / "color.exr").c_str());
  std::vector<float> rgba(4 * 6, -1.0f);
  Imf::FrameBuffer frame;
  const char* names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c)
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgba.data() + c),
                                      4 * sizeof(float), 4 * sizeof(float) * 3));
  file.setFrameBuffer(frame);
  file.readPixels(0, 1);
  EXPECT_EQ(rgba, picture.rgba);
}

}  // namespace
}  // namespace voxspan
