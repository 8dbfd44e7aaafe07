#include "insitu/views/color_map.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "render/srgb8_image.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

// The published stops, sRGB 0xRRGGBB, evenly spaced over [0, 1].
constexpr std::uint32_t kViridis[] = {0x440154, 0x482475, 0x414487, 0x355f8d, 0x2a788e, 0x21918c,
                                      0x22a884, 0x44bf70, 0x7ad151, 0xbddf26, 0xfde725};
constexpr std::uint32_t kPlasma[] = {0x0d0887, 0x41049d, 0x6a00a8, 0x8f0da4, 0xb12a90, 0xcc4778,
                                     0xe16462, 0xf2844b, 0xfca636, 0xfcce25, 0xf0f921};
constexpr std::uint32_t kInferno[] = {0x000004, 0x160b39, 0x420a68, 0x6a176e, 0x932667, 0xbc3754,
                                      0xdd513a, 0xf37819, 0xfca50a, 0xf6d746, 0xfcffa4};
constexpr std::uint32_t kCoolwarm[] = {0x3b4cc0, 0x7b9ff9, 0xdddcdc, 0xf49a7b, 0xb40426};
constexpr std::uint32_t kGray[] = {0x000000, 0xffffff};

std::span<const std::uint32_t> stops(ColorMap map) {
  switch (map) {
    case ColorMap::viridis: return kViridis;
    case ColorMap::plasma: return kPlasma;
    case ColorMap::inferno: return kInferno;
    case ColorMap::coolwarm: return kCoolwarm;
    case ColorMap::gray: return kGray;
  }
  return kGray;
}

glm::vec3 linear_rgb(std::uint32_t hex) {
  return {srgb8_to_linear((hex >> 16) & 0xff), srgb8_to_linear((hex >> 8) & 0xff),
          srgb8_to_linear(hex & 0xff)};
}

}  // namespace

glm::vec3 map_color(ColorMap map, double t) {
  const std::span<const std::uint32_t> s = stops(map);
  const double x = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0) * double(s.size() - 1);
  const std::size_t k = std::min(std::size_t(x), s.size() - 2);
  const float f = float(x - double(k));
  return glm::mix(linear_rgb(s[k]), linear_rgb(s[k + 1]), f);
}

double ColorAxis::t(double v) const {
  if (scale == ColorScale::linear) return (v - lo) / (hi - lo);
  if (!(v > 0)) return -std::numeric_limits<double>::infinity();
  return std::log(v / lo) / std::log(hi / lo);
}

double ColorAxis::value(double at) const {
  if (scale == ColorScale::linear) return lo + at * (hi - lo);
  return lo * std::pow(hi / lo, at);
}

ColorAxis display_axis(const ValueSpan& seen, ColorScale scale) {
  if (scale == ColorScale::log) {
    const double lo = seen.lo_positive, hi = seen.hi;
    if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi)) return {1, 10, scale};
    if (hi <= lo * (1 + 1e-12)) return {lo / 1.1, hi * 1.1, scale};
    return {lo, hi, scale};
  }
  const double lo = seen.lo, hi = seen.hi;
  if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi)) return {0, 1, scale};
  if (hi - lo <= 1e-12 * std::max(std::abs(lo), std::abs(hi))) {
    const double pad = lo == 0 ? 0.5 : 0.01 * std::abs(lo);
    return {lo - pad, hi + pad, scale};
  }
  return {lo, hi, scale};
}

ColorAxis color_axis(const std::optional<std::array<double, 2>>& range, const ValueSpan& seen,
                     ColorScale scale) {
  if (range) return {(*range)[0], (*range)[1], scale};
  return display_axis(seen, scale);
}

ColorAxis ViewColorAxis::operator()(const std::optional<std::array<double, 2>>& range,
                                    const ValueSpan& seen, ColorScale scale) const {
  const bool values = seen.lo <= seen.hi, none_positive = !(seen.lo_positive <= seen.hi);
  if (!range && scale == ColorScale::log && values && none_positive && !told_) {
    told_ = true;
    if (reports_)
      log_warning("view ", view_, ": scale log, but no value of \"", quantity_,
                  "\" is above 0 (they run from ", seen.lo, " to ", seen.hi,
                  "): all take the map's lowest colour; scale: linear, or a range, shows them "
                  "(said once)");
  }
  return color_axis(range, seen, scale);
}

}  // namespace voxspan
