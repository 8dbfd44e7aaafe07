#include "insitu/outputs/formats/png_image.h"

#include <png.h>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>

#include "insitu/outputs/writer/atomic_file.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

double srgb_encode(double c) {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// 2^16 steps of linear light: fine enough that the dark end (slope 12.92) still rounds to the
// exact 8-bit value, and ~50x faster than pow per channel.
constexpr int kLutBits = 16;
const std::array<std::uint8_t, (1 << kLutBits) + 1>& srgb_lut() {
  static const auto lut = [] {
    std::array<std::uint8_t, (1 << kLutBits) + 1> t{};
    for (std::size_t i = 0; i < t.size(); ++i)
      t[i] = static_cast<std::uint8_t>(
          std::lround(255.0 * srgb_encode(double(i) / double(1 << kLutBits))));
    return t;
  }();
  return lut;
}

std::uint8_t to_unorm8(float v) {
  if (!(v > 0)) return 0;
  if (v >= 1) return 255;
  return static_cast<std::uint8_t>(std::lround(v * 255.0f));
}

}  // namespace

std::uint8_t linear_to_srgb8(float linear) {
  if (!(linear > 0)) return 0;  // also NaN
  if (linear >= 1) return 255;
  return srgb_lut()[static_cast<std::size_t>(linear * float(1 << kLutBits) + 0.5f)];
}

ImageRGBA8 linear_to_srgb8(std::span<const float> rgba, int width, int height, bool bottom_up) {
  std::size_t count = std::size_t(width) * std::size_t(height);
  if (width <= 0 || height <= 0 || rgba.size() != count * 4)
    throw make_error("linear_to_srgb8: ", rgba.size(), " floats for a ", width, "x", height,
                     " RGBA image (expected ", count * 4, ")");
  ImageRGBA8 out{width, height, std::vector<std::uint8_t>(count * 4)};
  for (int y = 0; y < height; ++y) {
    const float* src = rgba.data() + std::size_t(bottom_up ? height - 1 - y : y) * width * 4;
    std::uint8_t* dst = out.pixels.data() + std::size_t(y) * width * 4;
    for (int x = 0; x < width; ++x, src += 4, dst += 4) {
      dst[0] = linear_to_srgb8(src[0]);
      dst[1] = linear_to_srgb8(src[1]);
      dst[2] = linear_to_srgb8(src[2]);
      dst[3] = to_unorm8(src[3]);
    }
  }
  return out;
}

std::string encode_png(std::span<const std::uint8_t> rgba, int width, int height, bool bottom_up) {
  std::size_t expected = std::size_t(width) * std::size_t(height) * 4;
  if (width <= 0 || height <= 0 || rgba.size() != expected)
    throw make_error("encode_png: ", rgba.size(), " bytes for a ", width, "x", height,
                     " RGBA8 image (expected ", expected, ")");
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGBA;
  image.flags = PNG_IMAGE_FLAG_FAST;  // frames: zlib speed over the last few percent of size
  png_int_32 stride = static_cast<png_int_32>(width * 4) * (bottom_up ? -1 : 1);
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, rgba.data(), stride, nullptr))
    throw make_error("PNG encoding failed: ", image.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, rgba.data(), stride, nullptr))
    throw make_error("PNG encoding failed: ", image.message);
  bytes.resize(size);
  return bytes;
}

ImageRGBA8 decode_png(std::string_view bytes) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
    throw make_error("not a readable PNG: ", image.message);
  image.format = PNG_FORMAT_RGBA;
  ImageRGBA8 out{static_cast<int>(image.width), static_cast<int>(image.height), {}};
  out.pixels.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr)) {
    png_image_free(&image);
    throw make_error("PNG decoding failed: ", image.message);
  }
  return out;
}

ImageRGBA8 read_png(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw make_error("cannot read ", path.string());
  std::ostringstream s;
  s << in.rdbuf();
  try {
    return decode_png(s.str());
  } catch (const Error& e) {
    throw make_error(path.string(), ": ", e.what());
  }
}

void write_png(const std::filesystem::path& path, const ImageRGBA8& image, bool sync) {
  write_file_atomically(path, encode_png(image), sync);
}

}  // namespace voxspan
