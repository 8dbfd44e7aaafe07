// insitu/views/legend.h - what a colour-mapped view writes into its picture so that the colours
// can be read: the colour bar with its values, in a 5x7 pixel font (digits, the signs and a
// few letters, enough for numbers and axis names) drawn light on a dark outline. Standard
// library and glm only; no font files.
#pragma once

#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "insitu/views/color_map.h"
#include "render/float_image.h"

namespace voxspan {

// Screen pixels per font pixel for a picture of this height (1 up to 719 rows, 2 from 720...).
int text_scale(int image_height);
// Width in pixels of `text` at `scale` (6 font pixels per character, the last one's gap kept).
int text_width(std::string_view text, int scale);
// Draws `text` with its top-left corner at (x, y), clipped to the picture; characters outside
// the font show as blanks.
void draw_text(FloatImage& picture, int x, int y, std::string_view text, int scale,
               glm::vec3 colour = glm::vec3(0.9f));
// A value as the legend prints it: three significant digits ("0.125", "-3.5e+04").
std::string legend_number(double value);
// The colour bar at the right edge (the map from `hi` at its top to `lo` at its bottom) with the
// two values and the middle one beside it.
void draw_color_bar(FloatImage& picture, ColorMap map, double lo, double hi);

}  // namespace voxspan
