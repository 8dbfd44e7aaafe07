// insitu/views/legend.h - what a colour-mapped view writes into its picture so that colours and
// places can be read: the colour bar with its title and values, a 2D view's axes, a view's
// caption, in a 5x7 pixel font (printable ASCII) drawn light on a dark outline. Standard library
// and glm only; no font files.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "insitu/views/color_map.h"
#include "render/float_image.h"
#include "render/srgb8_image.h"

namespace voxspan {

// Screen pixels per font pixel for a picture of this height (1 up to 719 rows, 2 from 720...).
int text_scale(int image_height);
// Width in pixels of `text` at `scale` (6 font pixels per character, the last one's gap kept).
int text_width(std::string_view text, int scale);
// The text's colour (linear), unless told.
inline const glm::vec3 kTextColour(0.9f);
// Draws `text` with its top-left corner at (x, y), clipped to the picture; characters outside
// the font show as blanks.
void draw_text(FloatImage& picture, int x, int y, std::string_view text, int scale,
               glm::vec3 colour = kTextColour);
// A view's caption (insitu/config/caption.h) at the picture's top left; on an 8-bit sRGB
// picture the bytes linear_to_srgb8 gives the float one's caption (the same once encoded).
void draw_caption(FloatImage& picture, std::string_view text);
void draw_caption(ImageRGBA8& picture, std::string_view text);
// A value as the legend prints it: three significant digits ("0.125", "-3.5e+04"), more where
// `apart` (how far apart the values printed beside it are) needs them to tell them apart
// ("300", "300.025", "300.05", not "300" three times); a value under a millionth of `apart`
// prints as 0 (a field's minimum of 2.5e-16 beside a maximum of 1).
std::string legend_number(double value, double apart = 0);
enum class BarSide : std::uint8_t { right, left };
// The colour bar at the right (or left) edge, the map from the axis' hi at its top to its lo at
// its bottom, with the two values and the one at its middle (on a log scale their geometric
// mean) beside it and `title` (what the colours are, view_keys.h: color_bar_title) above it.
void draw_color_bar(FloatImage& picture, ColorMap map, const ColorAxis& axis,
                    std::string_view title, BarSide side = BarSide::right);

// The columns from its edge that draw_color_bar covers with the bar and its values (the title
// above them is not counted: it sits over the top tenth of the picture, as wide as it is long).
int color_bar_columns(int width, int height);

// The pixels along each edge of a width x height picture that a 2D view's legend may cover:
// the colour bar with its labels (right), the axes' labels (left, bottom), the caption (top).
// All zero where they would leave the data less than half the picture each way (tiny pictures:
// the legend goes over the data there).
struct LegendMargins {
  int left = 0, right = 0, top = 0, bottom = 0;
};
LegendMargins legend_margins(int width, int height);
// What a 3D view's colour bar at `side` covers (color_bar_columns at that edge), for automatic
// framing to keep the fluid out of (view_framing.h); none where it would leave the fluid less
// than half the picture's width.
LegendMargins color_bar_margins(int width, int height, BarSide side);
// Each side the larger of the two: the margins of every legend a view draws.
LegendMargins covering(const LegendMargins& a, const LegendMargins& b);

// An axis along an edge of a 2D picture: the world coordinate at its two ends (left to right,
// bottom to top; `from` > `to` when the coordinate falls that way) and its name ("x").
struct Axis {
  double from = 0, to = 1;
  std::string_view name;
};
// Ticks at round values (1, 2 or 5 times a power of ten, about five per axis) along the bottom
// and the left edge, each with its value; the middle one also names its axis ("x=0.4"). Not in
// pictures smaller than these (no room for the labels):
inline constexpr int kAxesMinWidth = 160, kAxesMinHeight = 120;
void draw_axes(FloatImage& picture, const Axis& horizontal, const Axis& vertical);

}  // namespace voxspan
