// insitu/views/surface_colors.h - a surface view's `color_by`: a particle attribute (a vector:
// its magnitude) SPH-interpolated at each pixel's first surface (the point at the renderer's
// first-hit distance: the first span entry) from the owned particles, Shepard-normalised (the
// kernel's sum is truncated at a free surface, where every point of it lies), with h = 1.3
// spacings and the cubic spline (insitu/views/sph_points.h), then mapped through the colour map
// into the shaded picture, with the colour bar.
//
// The colour in the picture (docs/runtime.md): opaque, it replaces the lit albedo's hue and keeps
// its luminance (the map's colour times the lighting); translucent and refractive, it replaces
// the hue of the light the fluid sends back through its first surface, and the share the surface
// reflects (Schlick's Fresnel term at the first hit's normal, from the neighbouring pixels'
// first-hit points, averaged over the pixel and its hit neighbours as the shading averages it)
// keeps the shading's own colour, so the sky's highlights still read as water.
//
// Reads: the owned particles (positions, the attribute, mass and density when both are there),
// the first-hit distances on the process that shades. In an MPI job rank 0 sends the distances
// to every rank, each sums its owned particles' part at every first-hit point and rank 0 adds
// them up (exact, like the slice's sums). Costs: one broadcast of width x height floats and two
// sums of a double per hit pixel (MPI), one pass over the owned particles, and per hit pixel the
// particles within the kernel's support; hit pixels in parallel (oneTBB).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "insitu/views/legend.h"
#include "insitu/views/sph_points.h"
#include "insitu/views/view_keys.h"
#include "render/camera.h"
#include "render/float_image.h"
#include "render/recorder.h"
#include "render/shade_options.h"

namespace voxspan {

class Communicator;

namespace pass {
inline constexpr StatName color_sum{"color_sum"};    // collective: the sums at the first hits
inline constexpr StatName color_draw{"color_draw"};  // the picture's colours and the bar
}  // namespace pass

class SurfaceColors {
 public:
  // `key`: the key path of color_by in messages. Throws voxspan::Error when the spacing is
  // unknown (the smoothing length is 1.3 spacings).
  SurfaceColors(const ColorBySettings& settings, std::string view_name, std::string key,
                double spacing, Communicator* comm);
  SurfaceColors(const SurfaceColors&) = delete;  // quantity_ points into settings_
  SurfaceColors& operator=(const SurfaceColors&) = delete;

  // The values at the first hits of `first_hit` (distances along each pixel's ray, 0: none; null
  // on a process that does not shade), seen with `camera`. Collective in an MPI job: every rank
  // calls it; `failure` says why this process has no picture where it should have one, and all
  // throw when any rank failed.
  void sample(const ParticleView& particles, const Camera& camera, const FloatImage* first_hit,
              const std::string& failure);
  // The sampled colours into the shaded picture by `shade`'s mode (see above), then the colour
  // bar at `side` when the settings want a legend. On the process that shades.
  void paint(const ShadeOptions& shade, FloatImage& picture, BarSide side) const;

  ColorAxis axis() const;  // the colour map's on this step
  // What paint's colour bar at `side` covers in a width x height picture (none without one).
  LegendMargins bar_margins(int width, int height, BarSide side) const {
    return settings_.legend ? color_bar_margins(width, height, side) : LegendMargins{};
  }
  // The value at pixel (x, y): NaN where no first hit has a particle within reach.
  double value(int x, int y) const;

 private:
  void sum_ranks(const ParticleView& particles);
  glm::dvec3 normal_at(int x, int y, glm::dvec3 dir) const;
  double reflectance(int x, int y) const;
  float reference_luminance(const ShadeOptions& shade, const FloatImage& picture) const;

  const ColorBySettings settings_;
  const std::string bar_title_;
  const std::string key_;
  SliceQuantity quantity_;
  Communicator* const comm_;  // null in one process
  const ViewColorAxis color_axis_;
  ViewFrame frame_;
  std::vector<float> distances_;        // per pixel, from the shading process
  std::vector<std::int64_t> point_of_;  // per pixel: its index in points_, -1: no hit
  std::vector<glm::dvec3> points_;
  std::vector<double> values_;           // per point; NaN where no particle reaches
  mutable std::vector<double> fresnel_;  // per point, paint's: Schlick's term at its normal
  SphPoints sums_;
};

}  // namespace voxspan
