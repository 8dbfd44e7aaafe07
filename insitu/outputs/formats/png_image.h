// insitu/outputs/formats/png_image.h - 8-bit sRGB PNG frames from the renderer's images.
//
// The shade passes produce linear RGBA floats (or RGBA8 already in sRGB); PNG stores 8-bit
// sRGB with an sRGB chunk, top row first. GL read-backs are bottom row first: pass
// bottom_up = true. Encoding goes to memory (libdeflate), so the file itself is written
// atomically; decoding is libpng's.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "render/float_image.h"
#include "render/srgb8_image.h"  // ImageRGBA8, linear_to_srgb8

namespace voxspan {

// How a frame is compressed: each row filtered (PNG's filter types; `adaptive` picks one per
// row by libpng's heuristic, the least sum of absolute differences), then one deflate stream at
// libdeflate's `level` (0 stored, 1 fastest ... 12 smallest). Every setting decodes to the same
// pixels; they differ in time and bytes. The default, level 4 of rows filtered by Sub, is
// measured in docs/benchmarks.md, "PNG encoding" (Sub gave the smallest files at every level,
// on every picture there): about 30 ms and 0.7 MB a 1920x1080 frame on one core.
enum class PngFilter { none, sub, up, average, paeth, adaptive };
struct PngEncoding {
  int level = 4;
  PngFilter filter = PngFilter::sub;
  bool operator==(const PngEncoding&) const = default;
};

// 8-bit RGBA with an sRGB chunk (IHDR, sRGB, IDAT, IEND). Throws voxspan::Error when the
// sizes do not match or the level is outside 0..12.
std::string encode_png(std::span<const std::uint8_t> rgba, int width, int height,
                       bool bottom_up = false, PngEncoding encoding = {});
inline std::string encode_png(const ImageRGBA8& image, PngEncoding encoding = {}) {
  return encode_png(image.pixels, image.width, image.height, false, encoding);
}
ImageRGBA8 decode_png(std::string_view bytes);  // any PNG, as 8-bit sRGB RGBA
ImageRGBA8 read_png(const std::filesystem::path& path);

// encode_png + write_file_atomically (temp name, fsync when sync, rename).
void write_png(const std::filesystem::path& path, const ImageRGBA8& image, bool sync = true,
               PngEncoding encoding = {});

// A view's linear picture as its PNG (linear_to_srgb8, then as above): what the PNG frames,
// the Cinema database and the live page show, the same bytes for the same encoding.
std::string encode_picture_png(const FloatImage& picture, PngEncoding encoding = {});
void write_picture_png(const std::filesystem::path& path, const FloatImage& picture,
                       bool sync = true, PngEncoding encoding = {});

}  // namespace voxspan
