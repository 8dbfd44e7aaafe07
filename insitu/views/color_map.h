// insitu/views/color_map.h - colour maps for quantities on particles and slices: perceptually
// uniform (viridis, plasma, inferno, matplotlib's), diverging (coolwarm, Moreland's) and gray.
// Each is its published colours at eleven (coolwarm: five) evenly spaced stops, in sRGB, and
// map_color interpolates between them in linear RGB, which is what the shading and the PNG
// encoding (insitu/outputs/formats/png_image.h) expect. Standard library and glm only.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "render/enum_names.h"

namespace voxspan {

enum class ColorMap : std::uint8_t { viridis, plasma, inferno, coolwarm, gray };
inline constexpr EnumName<ColorMap> kColorMapNames[] = {{"viridis", ColorMap::viridis},
                                                        {"plasma", ColorMap::plasma},
                                                        {"inferno", ColorMap::inferno},
                                                        {"coolwarm", ColorMap::coolwarm},
                                                        {"gray", ColorMap::gray}};

// How values spread along a colour map: evenly, or by their logarithm (densities of
// self-gravitating gas, vorticity: fields that span decades, as SPLASH and yt show them).
enum class ColorScale : std::uint8_t { linear, log };
inline constexpr EnumName<ColorScale> kColorScaleNames[] = {{"linear", ColorScale::linear},
                                                            {"log", ColorScale::log}};

// The colour at t in [0, 1] (clamped; NaN gives the map's lowest colour), linear RGB.
glm::vec3 map_color(ColorMap map, double t);

// The values a colour map spans, lo at its start and hi at its end (on a log scale both above
// 0), and how they spread along it.
struct ColorAxis {
  double lo = 0, hi = 1;
  ColorScale scale = ColorScale::linear;
  // v's place along the map: 0 at lo, 1 at hi, unclamped (on a log scale, a value at or under 0
  // lies below the map: -infinity).
  double t(double v) const;
  // The value at place t: the legend's labels.
  double value(double t) const;
};

// The smallest and largest finite values seen, the smallest above 0 (where a log scale's
// automatic range starts), and how many were NaN or infinite.
struct ValueSpan {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, lo_positive = lo;
  double non_finite = 0;
  void add(double v) {
    if (!std::isfinite(v)) {
      ++non_finite;
      return;
    }
    lo = std::min(lo, v), hi = std::max(hi, v);
    if (v > 0) lo_positive = std::min(lo_positive, v);
  }
  void add(const ValueSpan& o) {
    lo = std::min(lo, o.lo), hi = std::max(hi, o.hi),
    lo_positive = std::min(lo_positive, o.lo_positive);
    non_finite += o.non_finite;
  }
};

// Every rank's values seen, on every rank: one collective minimum (`comm`: a Communicator,
// insitu/parallel/communicator.h) over the span's ends; non_finite becomes the most on a rank.
template <class Comm> void span_over_ranks(Comm& comm, ValueSpan& v) {
  double ends[4] = {v.lo, -v.hi, v.lo_positive, -v.non_finite};
  comm.min(ends);
  v.lo = ends[0], v.hi = -ends[1], v.lo_positive = ends[2], v.non_finite = -ends[3];
}

// The automatic axis for the values `seen`: their smallest (on a log scale: smallest above 0)
// to their largest, widened about them when (nearly) equal so that the map's middle shows;
// [0, 1] ([1, 10] on a log scale) when there are none.
ColorAxis display_axis(const ValueSpan& seen, ColorScale scale);
// `range` where given (a config's), else display_axis.
ColorAxis color_axis(const std::optional<std::array<double, 2>>& range, const ValueSpan& seen,
                     ColorScale scale);

// A view's color_axis over its steps, which warns once (where `reports`: one rank) when a log
// scale's automatic range finds values but none above 0 to start from: every one then takes
// the map's lowest colour under a legend of [1, 10].
class ViewColorAxis {
 public:
  ViewColorAxis(std::string view, std::string quantity, bool reports)
      : view_(std::move(view)), quantity_(std::move(quantity)), reports_(reports) {}
  ColorAxis operator()(const std::optional<std::array<double, 2>>& range, const ValueSpan& seen,
                       ColorScale scale) const;

 private:
  std::string view_, quantity_;
  bool reports_;
  mutable bool told_ = false;  // a note, not the axis: the views' const paths may say it
};

}  // namespace voxspan
