// insitu/outputs/formats/png_image.h - 8-bit sRGB PNG frames from the renderer's images.
//
// The shade passes produce linear RGBA floats (or RGBA8 already in sRGB); PNG stores 8-bit
// sRGB with an sRGB chunk, top row first. GL read-backs are bottom row first: pass
// bottom_up = true. Encoding goes to memory, so the file itself is written atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace voxspan {

struct ImageRGBA8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4, top row first
};

// Linear RGB in [0, 1] (clamped; NaN reads as 0) to 8-bit sRGB; alpha stays linear.
std::uint8_t linear_to_srgb8(float linear);
ImageRGBA8 linear_to_srgb8(std::span<const float> rgba, int width, int height,
                           bool bottom_up = false);

// Throws voxspan::Error when the sizes do not match or libpng fails.
std::string encode_png(std::span<const std::uint8_t> rgba, int width, int height,
                       bool bottom_up = false);
inline std::string encode_png(const ImageRGBA8& image) {
  return encode_png(image.pixels, image.width, image.height);
}
ImageRGBA8 decode_png(std::string_view bytes);  // any PNG, as 8-bit sRGB RGBA
ImageRGBA8 read_png(const std::filesystem::path& path);

// encode_png + write_file_atomically (temp name, fsync when sync, rename).
void write_png(const std::filesystem::path& path, const ImageRGBA8& image, bool sync = true);

}  // namespace voxspan
