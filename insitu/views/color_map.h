// insitu/views/color_map.h - colour maps for quantities on particles and slices: perceptually
// uniform (viridis, plasma, inferno, matplotlib's), diverging (coolwarm, Moreland's) and gray.
// Each is its published colours at eleven (coolwarm: five) evenly spaced stops, in sRGB, and
// map_color interpolates between them in linear RGB, which is what the shading and the PNG
// encoding (insitu/outputs/formats/png_image.h) expect. Standard library and glm only.
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "render/enum_names.h"

namespace voxspan {

enum class ColorMap : std::uint8_t { viridis, plasma, inferno, coolwarm, gray };
inline constexpr EnumName<ColorMap> kColorMapNames[] = {{"viridis", ColorMap::viridis},
                                                        {"plasma", ColorMap::plasma},
                                                        {"inferno", ColorMap::inferno},
                                                        {"coolwarm", ColorMap::coolwarm},
                                                        {"gray", ColorMap::gray}};

// The colour at t in [0, 1] (clamped; NaN gives the map's lowest colour), linear RGB.
glm::vec3 map_color(ColorMap map, double t);

// The automatic range for values from lo to hi: [lo, hi], widened about them when (nearly)
// equal so that the map's middle shows; [0, 1] when there are none (lo > hi or not finite).
std::array<double, 2> display_range(double lo, double hi);

}  // namespace voxspan
