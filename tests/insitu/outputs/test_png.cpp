// PNG frames: sRGB conversion, encoding, row order, atomic files.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "insitu/outputs/formats/png_image.h"
#include "tests/support/temp_folder.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

int exact_srgb8(double linear) {
  double c = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
  return int(std::lround(255 * std::clamp(c, 0.0, 1.0)));
}

TEST(Png, LinearToSrgbMatchesTheStandardCurve) {
  EXPECT_EQ(linear_to_srgb8(0.f), 0);
  EXPECT_EQ(linear_to_srgb8(1.f), 255);
  EXPECT_EQ(linear_to_srgb8(0.5f), 188);
  EXPECT_EQ(linear_to_srgb8(0.22f), 129);
  EXPECT_EQ(linear_to_srgb8(-3.f), 0);
  EXPECT_EQ(linear_to_srgb8(7.f), 255);
  EXPECT_EQ(linear_to_srgb8(std::nanf("")), 0);
  // The table against the formula, at 100 000 points: off by at most one step, and only where
  // the exact value sits on a rounding edge.
  int off = 0;
  for (int i = 0; i <= 100000; ++i) {
    double v = i / 100000.0;
    int d = std::abs(int(linear_to_srgb8(float(v))) - exact_srgb8(v));
    ASSERT_LE(d, 1) << v;
    off += d;
  }
  EXPECT_LT(off, 500);
}

TEST(Png, RoundTripsPixelsAndFlipsBottomUpImages) {
  const int w = 5, h = 3;
  std::vector<float> linear(w * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = &linear[(y * w + x) * 4];
      p[0] = x / 4.f, p[1] = y / 2.f, p[2] = 0.25f, p[3] = 1.f - 0.25f * y;
    }
  ImageRGBA8 top_down = linear_to_srgb8(linear, w, h);
  ImageRGBA8 decoded = decode_png(encode_png(top_down));
  EXPECT_EQ(decoded.width, w);
  EXPECT_EQ(decoded.height, h);
  EXPECT_EQ(decoded.pixels, top_down.pixels);
  EXPECT_EQ(decoded.pixels[0 * 4 + 1], 0);          // row 0 is y = 0
  EXPECT_EQ(decoded.pixels[(2 * w) * 4 + 3], 128);  // alpha stays linear: 0.5 -> 128
  // A GL read-back (bottom row first) comes out upright.
  ImageRGBA8 flipped = linear_to_srgb8(linear, w, h, /*bottom_up=*/true);
  ImageRGBA8 again = decode_png(encode_png(flipped.pixels, w, h, /*bottom_up=*/true));
  EXPECT_EQ(again.pixels, top_down.pixels);
}

TEST(Png, WritesAtomicallyAndReadsBack) {
  test::TempFolder dir;
  ImageRGBA8 image{2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 9}};
  write_png(dir / "f.png", image);
  EXPECT_EQ(read_png(dir / "f.png").pixels, image.pixels);
  EXPECT_EQ(test::count_temp_files(dir.path()), 0u);
}

TEST(Png, BadInputIsAClearError) {
  EXPECT_THROW(encode_png(std::vector<std::uint8_t>(10), 2, 2), Error);
  EXPECT_THROW(linear_to_srgb8(std::vector<float>(3), 1, 1), Error);
  try {
    decode_png("not a png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a readable PNG"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace voxspan
