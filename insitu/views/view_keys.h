// insitu/views/view_keys.h - config keys that several view kinds share, written once: an SPH
// sum's (the slice's and the volume view's), a colour map's, and the colouring by an attribute
// of the particles and surface views.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/schema.h"
#include "insitu/views/color_map.h"
#include "render/sph_kernel.h"
#include "voxspan/log.h"

namespace voxspan {

// h = 1.3 spacings when the view does not say: PySPH's usual hdx.
inline constexpr double kAutoSmoothingFactor = 1.3;

// A smoothing length in other units than the positions (cm for m) makes each sample sum a
// million particles (a step takes minutes) or none (an empty picture): said at start-up. SPH
// codes take h from 1 to 2 spacings (up to 4 where h names the kernel's whole support).
inline void warn_of_odd_smoothing(const std::string& key, std::optional<double> h, double spacing) {
  if (!h || !(spacing > 0)) return;
  const double spacings = *h / spacing;
  if (spacings >= 0.25 && spacings <= 6) return;
  log_warning(key, " ", *h, " is ", spacings, " particle spacings (", spacing,
              "): ", spacings > 6 ? "each sample then sums about " : "a sample then reaches about ",
              spacings > 6 ? std::to_string(std::lround(4.2 * spacings * spacings * spacings))
                           : std::string("no"),
              " particles; h is usually 1 to 2 spacings: check its units");
}

// The keys of an SPH sum, for any settings with these members: quantity, kernel,
// smoothing_length, smoothing_attribute, shepard, mass, density.
template <class S>
std::vector<schema::Key<S>> sph_sum_keys(std::string quantity_help, std::string shepard_help) {
  return {schema::text("quantity", &S::quantity, std::move(quantity_help)),
          schema::choice("kernel", &S::kernel, kSphKernelNames,
                         "the SPH kernel W, normalised in 3D (in 2D for a run in a plane)"),
          schema::number_or_auto("smoothing_length", &S::smoothing_length, schema::above(0),
                                 "h, world units; `auto` = 1.3 particle spacings"),
          schema::text("smoothing_attribute", &S::smoothing_attribute,
                       "the attribute with each particle's h (astrophysics codes); empty: "
                       "smoothing_length for all"),
          schema::flag("shepard", &S::shepard, std::move(shepard_help)),
          schema::text("mass", &S::mass,
                       "the mass attribute; without it or `density`, m / rho = spacing^3"),
          schema::text("density", &S::density, "the density attribute")};
}

// `color_map`, `range`, `scale` and `units`, for any settings with these members; `range_auto`
// says what `auto` takes.
template <class S>
std::vector<schema::Key<S>> color_map_keys(std::string map_help, std::string range_auto) {
  return {
      schema::choice("color_map", &S::color_map, kColorMapNames, std::move(map_help)),
      schema::interval_or_auto(
          "range", &S::range,
          "the values at the colour map's ends; `auto` = " + std::move(range_auto) +
              " (on a `log` scale: the smallest above 0)"),
      schema::choice("scale", &S::scale, kColorScaleNames,
                     "how the values spread along the map: `linear`, or `log` (by their "
                     "logarithm, for fields spanning decades; values at or under 0 take "
                     "its lowest colour, and a view with none above 0 says so)"),
      schema::text("units", &S::units,
                   "the values' units, shown after the colour bar's title (the quantity's "
                   "name): `m/s` on `velocity` gives \"velocity [m/s]\"; empty: the name alone")};
}

// One h for all, or each particle's own: not both (called by the SPH sums' checks).
template <class S> void check_sph_sum(yaml::MapReader& r, const S& s) {
  if (s.smoothing_length && !s.smoothing_attribute.empty())
    r.checker().error(r.find("smoothing_length"), r.path("smoothing_length"),
                      "smoothing_attribute \"" + s.smoothing_attribute +
                          "\" gives each particle's h: leave smoothing_length out (or at auto)");
}

// A log scale's range must lie above 0, and the units must be in the picture's font (called
// by each view kind's check).
template <class S> void check_color_axis(yaml::MapReader& r, const S& s) {
  for (char c : s.units)
    if (c < ' ' || c > '~') {
      r.checker().error(r.find("units"), r.path("units"),
                        "holds a character the picture's font lacks (printable ASCII only: "
                        "`degC` for a degree sign, `um` for micro)");
      break;
    }
  if (s.scale == ColorScale::log && s.range && !((*s.range)[0] > 0))
    r.checker().error(r.find("range"), r.path("range"),
                      "a `log` scale needs a range above 0; got [" +
                          yaml::number_text((*s.range)[0]) + ", " +
                          yaml::number_text((*s.range)[1]) + "]");
}

// Colouring by a particle attribute (the particles and surface views): which, through what map
// and range, and whether the colour bar shows.
struct ColorBySettings {
  std::string color_by;  // the attribute (a vector: its magnitude); empty: none
  ColorMap color_map = ColorMap::viridis;
  std::string units;                           // after the colour bar's title; empty: none
  std::optional<std::array<double, 2>> range;  // nullopt = the picture's min and max
  ColorScale scale = ColorScale::linear;
  bool legend = true;
  bool operator==(const ColorBySettings&) const = default;
};

// `color_by` (`color_by_help` says what it colours), the colour map's keys and `legend`;
// `range_auto` says what `auto` takes.
inline std::vector<schema::Key<ColorBySettings>> color_by_keys(std::string color_by_help,
                                                               std::string range_auto) {
  using S = ColorBySettings;
  return schema::joined(
      std::vector<schema::Key<S>>{schema::text("color_by", &S::color_by, std::move(color_by_help))},
      color_map_keys<S>("the colour map", std::move(range_auto)),
      std::vector<schema::Key<S>>{
          schema::flag("legend", &S::legend, "draw the colour bar with its values")});
}

// The colour bar's title: the quantity's name, with its units when given.
inline std::string color_bar_title(std::string_view quantity, std::string_view units) {
  std::string title(quantity);
  if (!units.empty()) title += " [" + std::string(units) + "]";
  return title;
}

}  // namespace voxspan
