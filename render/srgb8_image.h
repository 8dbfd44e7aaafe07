// render/srgb8_image.h - a picture as 8-bit sRGB RGBA (what PNG files and the live page hold),
// and the one definition of the encode from the shading's linear floats: a table of 2^16 + 1
// steps of linear light, which the GL renderer's conversion on the GPU reads too
// (render/gl/passes/srgb8_pack.h), so that both give the same bytes.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/float_image.h"

namespace voxspan {

struct ImageRGBA8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4, top row first
};

// Linear RGB in [0, 1] (clamped; NaN reads as 0) to 8-bit sRGB: the table's entry at
// linear * 2^16 + 0.5, rounded down (the nearest step). Off the exact curve by one only where
// the exact value sits on a rounding edge (tests/insitu/outputs/test_png.cpp).
std::uint8_t linear_to_srgb8(float linear);
// Alpha stays linear: round(alpha * 255), clamped; NaN reads as 0.
std::uint8_t linear_to_unorm8(float alpha);
// The exact inverse of the sRGB curve at an 8-bit value; linear_to_srgb8 of it gives the byte
// back (tested for all 256).
float srgb8_to_linear(std::uint32_t byte);

// The encode's table: entry i is the 8-bit sRGB value of linear light i / 2^kSrgb8TableBits.
inline constexpr int kSrgb8TableBits = 16;
std::span<const std::uint8_t> srgb8_table();

// A linear RGBA picture (`width` x `height`, bottom row first when `bottom_up`: GL read-backs)
// as 8-bit sRGB, top row first. Throws voxspan::Error when the sizes do not match.
ImageRGBA8 linear_to_srgb8(std::span<const float> rgba, int width, int height,
                           bool bottom_up = false);
// The same into `out`, reusing its storage (no allocation once it held a picture this size).
void linear_to_srgb8(const FloatImage& picture, ImageRGBA8& out);
// Back to linear floats (8-bit precision) into `out`, reusing its storage.
void srgb8_to_linear(const ImageRGBA8& picture, FloatImage& out);

}  // namespace voxspan
