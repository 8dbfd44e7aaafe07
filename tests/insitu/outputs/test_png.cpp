// PNG frames: sRGB conversion, encoding at every setting (decoded by libpng to the same
// pixels), row order, atomic files, outputs.png's compression_level.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include "insitu/outputs/formats/png_image.h"
#include "insitu/outputs/kinds/png_output.h"
#include "insitu/runtime/config_file.h"
#include "tests/support/error_message.h"
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

// What a picture that came as 8-bit sRGB gives a reader of floats (insitu/views/shared_picture.h)
// encodes to the same bytes: a PNG written from either is the same file.
TEST(Png, EachByteDecodedEncodesBackToItself) {
  for (std::uint32_t byte = 0; byte < 256; ++byte)
    EXPECT_EQ(linear_to_srgb8(srgb8_to_linear(byte)), byte) << byte;
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

constexpr PngFilter kFilters[] = {PngFilter::none,    PngFilter::sub,   PngFilter::up,
                                  PngFilter::average, PngFilter::paeth, PngFilter::adaptive};

// A picture with smooth parts (a sky-like gradient), edges, noise and varied alpha, at a width
// that is no multiple of anything: every filter's cases (first row, first pixel, wrap-around).
ImageRGBA8 test_picture(int w, int h) {
  ImageRGBA8 p{w, h, std::vector<std::uint8_t>(std::size_t(w) * h * 4)};
  std::mt19937 random(7);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* q = &p.pixels[(std::size_t(y) * w + x) * 4];
      const bool noisy = (x / 8 + y / 8) % 3 == 0;
      q[0] = std::uint8_t(noisy ? random() : 255 * y / h);
      q[1] = std::uint8_t(noisy ? random() : 200 - y);
      q[2] = std::uint8_t(x * 7 + y * 3);
      q[3] = std::uint8_t(x < w / 2 ? 255 : random());
    }
  return p;
}

TEST(Png, EverySettingRoundTripsThroughLibpng) {
  const ImageRGBA8 picture = test_picture(37, 23);
  for (int level = 0; level <= 12; ++level)
    for (PngFilter filter : kFilters) {
      SCOPED_TRACE("level " + std::to_string(level) + ", filter " + std::to_string(int(filter)));
      const ImageRGBA8 back = decode_png(encode_png(picture, {level, filter}));
      EXPECT_EQ(back.width, picture.width);
      EXPECT_EQ(back.height, picture.height);
      EXPECT_EQ(back.pixels, picture.pixels);
      // bottom-up rows come out upright at every filter (the filters read the row above)
      std::vector<std::uint8_t> flipped(picture.pixels.size());
      const std::size_t row = std::size_t(picture.width) * 4;
      for (int y = 0; y < picture.height; ++y)
        std::memcpy(&flipped[y * row], &picture.pixels[(picture.height - 1 - y) * row], row);
      EXPECT_EQ(
          decode_png(encode_png(flipped, picture.width, picture.height, true, {level, filter}))
              .pixels,
          picture.pixels);
    }
  // one pixel, one row, one column
  for (auto [w, h] : {std::pair{1, 1}, std::pair{9, 1}, std::pair{1, 9}}) {
    const ImageRGBA8 p = test_picture(w, h);
    for (PngFilter filter : kFilters)
      EXPECT_EQ(decode_png(encode_png(p, {4, filter})).pixels, p.pixels);
  }
}

// A frame the encoder before libdeflate wrote (libpng's, kept in the docs): the same pixels
// again at the default and at the settings around it.
TEST(Png, RenderedFramesComeBackTheSame) {
  const ImageRGBA8 frame = read_png(VOXSPAN_SOURCE_DIR "/docs/images/dambreak_opaque.png");
  ASSERT_EQ(frame.width, 960);
  for (PngEncoding e : {PngEncoding{}, PngEncoding{1, PngFilter::sub},
                        PngEncoding{6, PngFilter::paeth}, PngEncoding{1, PngFilter::adaptive}}) {
    const std::string bytes = encode_png(frame, e);
    EXPECT_EQ(decode_png(bytes).pixels, frame.pixels) << e.level;
    EXPECT_LT(bytes.size(), frame.pixels.size() / 4) << e.level;  // it does compress
  }
}

// 8-bit RGBA with the sRGB chunk, as libpng's simplified writer had it: IHDR, sRGB, IDAT, IEND.
TEST(Png, IsEightBitRgbaWithTheSrgbChunk) {
  const std::string png = encode_png(test_picture(5, 4));
  ASSERT_GT(png.size(), 8u + 25 + 13 + 12 + 12);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(std::string(png.substr(16, 8)), std::string("\0\0\0\x05\0\0\0\x04", 8));
  EXPECT_EQ(png[24], 8);  // bits per channel
  EXPECT_EQ(png[25], 6);  // RGBA
  EXPECT_EQ(png.substr(8 + 25 + 4, 4), "sRGB");
  EXPECT_EQ(png[8 + 25 + 8], 0);  // perceptual
  EXPECT_EQ(png.substr(8 + 25 + 13 + 4, 4), "IDAT");
  EXPECT_EQ(png.substr(png.size() - 8, 4), "IEND");
}

TEST(Png, CompressionLevelIsAKeyOfTheOutput) {
  EXPECT_EQ(load_config_string("").output<PngSettings>().compression_level, 4);
  EXPECT_EQ(PngEncoding{}, (PngEncoding{4, PngFilter::sub}));
  const Config c = load_config_string("outputs: {png: {compression_level: 1}}\n", "test.yaml");
  EXPECT_EQ(c.output<PngSettings>().compression_level, 1);
  const std::string e = test::error_message(
      [] { load_config_string("outputs: {png: {compression_level: 13}}\n", "test.yaml"); });
  EXPECT_NE(e.find("outputs.png.compression_level"), std::string::npos) << e;
}

TEST(Png, WritesAtomicallyAndReadsBack) {
  test::TempFolder dir;
  ImageRGBA8 image{2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 9}};
  write_png(dir / "f.png", image);
  EXPECT_EQ(read_png(dir / "f.png").pixels, image.pixels);
  write_png(dir / "g.png", image, false, {0, PngFilter::none});
  EXPECT_EQ(read_png(dir / "g.png").pixels, image.pixels);
  EXPECT_EQ(test::count_temp_files(dir.path()), 0u);
}

TEST(Png, BadInputIsAClearError) {
  EXPECT_THROW(encode_png(std::vector<std::uint8_t>(10), 2, 2), Error);
  EXPECT_THROW(encode_png(std::vector<std::uint8_t>(16), 2, 2, false, {13, PngFilter::sub}), Error);
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
