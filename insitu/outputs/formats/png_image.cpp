#include "insitu/outputs/formats/png_image.h"

#include <libdeflate.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "insitu/outputs/writer/atomic_file.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

void put_u32(std::uint8_t* at, std::uint32_t v) {
  at[0] = std::uint8_t(v >> 24), at[1] = std::uint8_t(v >> 16), at[2] = std::uint8_t(v >> 8),
  at[3] = std::uint8_t(v);
}

// Length, type, data, CRC of type and data.
void append_chunk(std::string& png, const char (&type)[5], const std::uint8_t* data,
                  std::size_t size) {
  std::array<std::uint8_t, 8> head{};
  put_u32(head.data(), std::uint32_t(size));
  std::memcpy(head.data() + 4, type, 4);
  std::uint32_t crc = static_cast<std::uint32_t>(libdeflate_crc32(0, head.data() + 4, 4));
  if (size > 0) crc = static_cast<std::uint32_t>(libdeflate_crc32(crc, data, size));
  png.append(reinterpret_cast<const char*>(head.data()), head.size());
  if (size > 0) png.append(reinterpret_cast<const char*>(data), size);
  std::array<std::uint8_t, 4> tail{};
  put_u32(tail.data(), crc);
  png.append(reinterpret_cast<const char*>(tail.data()), tail.size());
}

int paeth(int a, int b, int c) {  // left, above, upper left
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// One row through `filter` (not adaptive), 4 bytes a pixel; `prior` is null on the first row
// (zeros, as the PNG spec has it).
void filter_row(PngFilter filter, const std::uint8_t* x, const std::uint8_t* prior, std::size_t n,
                std::uint8_t* out) {
  constexpr std::size_t bpp = 4;
  switch (filter) {
    case PngFilter::none:
    case PngFilter::adaptive: std::memcpy(out, x, n); return;
    case PngFilter::sub:
      for (std::size_t i = 0; i < bpp; ++i) out[i] = x[i];
      for (std::size_t i = bpp; i < n; ++i) out[i] = std::uint8_t(x[i] - x[i - bpp]);
      return;
    case PngFilter::up:
      if (prior == nullptr) std::memcpy(out, x, n);
      else
        for (std::size_t i = 0; i < n; ++i) out[i] = std::uint8_t(x[i] - prior[i]);
      return;
    case PngFilter::average:
      for (std::size_t i = 0; i < n; ++i) {
        const int a = i >= bpp ? x[i - bpp] : 0, b = prior != nullptr ? prior[i] : 0;
        out[i] = std::uint8_t(x[i] - ((a + b) >> 1));
      }
      return;
    case PngFilter::paeth:
      if (prior == nullptr) {  // Paeth with a zero row above is Sub
        filter_row(PngFilter::sub, x, prior, n, out);
        return;
      }
      for (std::size_t i = 0; i < bpp; ++i) out[i] = std::uint8_t(x[i] - prior[i]);
      for (std::size_t i = bpp; i < n; ++i)
        out[i] = std::uint8_t(x[i] - paeth(x[i - bpp], prior[i], prior[i - bpp]));
      return;
  }
}

// The writer thread's compressor for a level, kept while the level stays.
libdeflate_compressor* compressor_at(int level) {
  struct Free {
    void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
  };
  thread_local std::unique_ptr<libdeflate_compressor, Free> compressor;
  thread_local int compressor_level = -1;
  if (!compressor || compressor_level != level) {
    compressor.reset(libdeflate_alloc_compressor(level));
    if (!compressor) throw make_error("PNG encoding: no deflate compressor at level ", level);
    compressor_level = level;
  }
  return compressor.get();
}

}  // namespace

std::string encode_png(std::span<const std::uint8_t> rgba, int width, int height, bool bottom_up,
                       PngEncoding encoding) {
  std::size_t expected = std::size_t(width) * std::size_t(height) * 4;
  if (width <= 0 || height <= 0 || rgba.size() != expected)
    throw make_error("encode_png: ", rgba.size(), " bytes for a ", width, "x", height,
                     " RGBA8 image (expected ", expected, ")");
  if (encoding.level < 0 || encoding.level > 12)
    throw make_error("encode_png: deflate level ", encoding.level, " (expected 0..12)");
  const std::size_t row = std::size_t(width) * 4;
  // The filtered rows, each after its filter type byte: what the IDAT stream compresses.
  const std::size_t filtered_size = std::size_t(height) * (row + 1);
  const auto filtered = std::make_unique_for_overwrite<std::uint8_t[]>(filtered_size);
  std::array<std::vector<std::uint8_t>, 5> trial;  // adaptive: each filter's row
  if (encoding.filter == PngFilter::adaptive)
    for (std::vector<std::uint8_t>& t : trial) t.resize(row);
  for (int y = 0; y < height; ++y) {
    const auto row_at = [&](int r) {
      return rgba.data() + std::size_t(bottom_up ? height - 1 - r : r) * row;
    };
    const std::uint8_t* x = row_at(y);
    const std::uint8_t* prior = y > 0 ? row_at(y - 1) : nullptr;
    std::uint8_t* out = filtered.get() + std::size_t(y) * (row + 1);
    if (encoding.filter != PngFilter::adaptive) {
      out[0] = static_cast<std::uint8_t>(encoding.filter);
      filter_row(encoding.filter, x, prior, row, out + 1);
      continue;
    }
    // libpng's heuristic: the filter whose bytes, read as signed, sum to the least magnitude.
    std::size_t best = 0;
    std::uint64_t best_sum = ~std::uint64_t(0);
    for (std::size_t f = 0; f < trial.size(); ++f) {
      filter_row(static_cast<PngFilter>(f), x, prior, row, trial[f].data());
      std::uint64_t sum = 0;
      for (std::uint8_t b : trial[f]) sum += b < 128 ? b : 256 - b;
      if (sum < best_sum) best = f, best_sum = sum;
    }
    out[0] = static_cast<std::uint8_t>(best);
    std::copy(trial[best].begin(), trial[best].end(), out + 1);
  }

  libdeflate_compressor* compressor = compressor_at(encoding.level);
  const std::size_t bound = libdeflate_zlib_compress_bound(compressor, filtered_size);
  const auto stream = std::make_unique_for_overwrite<std::uint8_t[]>(bound);
  const std::size_t size =
      libdeflate_zlib_compress(compressor, filtered.get(), filtered_size, stream.get(), bound);
  if (size == 0)
    throw make_error("PNG encoding failed: ", filtered_size, " bytes did not compress into ",
                     bound);

  // A chunk holds less than 2^31 bytes: the stream in as many IDAT chunks as that takes.
  constexpr std::size_t kMaxChunk = std::size_t(1) << 30;
  std::string png;
  png.reserve(8 + (12 + 13) + (12 + 1) + size + 12 * (size / kMaxChunk + 1) + 12);
  png.append("\x89PNG\r\n\x1a\n", 8);
  std::array<std::uint8_t, 13> ihdr{};
  put_u32(ihdr.data(), std::uint32_t(width));
  put_u32(ihdr.data() + 4, std::uint32_t(height));
  ihdr[8] = 8;  // bits per channel
  ihdr[9] = 6;  // RGBA; compression, filter method, interlace: 0
  append_chunk(png, "IHDR", ihdr.data(), ihdr.size());
  const std::uint8_t intent = 0;  // perceptual, as libpng's simplified writer put it
  append_chunk(png, "sRGB", &intent, 1);
  for (std::size_t at = 0; at < size; at += kMaxChunk)
    append_chunk(png, "IDAT", stream.get() + at, std::min(kMaxChunk, size - at));
  append_chunk(png, "IEND", nullptr, 0);
  return png;
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

void write_png(const std::filesystem::path& path, const ImageRGBA8& image, bool sync,
               PngEncoding encoding) {
  write_file_atomically(path, encode_png(image, encoding), sync);
}

std::string encode_picture_png(const FloatImage& picture, PngEncoding encoding) {
  return encode_png(linear_to_srgb8(picture.rgba, picture.width, picture.height), encoding);
}

void write_picture_png(const std::filesystem::path& path, const FloatImage& picture, bool sync,
                       PngEncoding encoding) {
  write_file_atomically(path, encode_picture_png(picture, encoding), sync);
}

}  // namespace voxspan
