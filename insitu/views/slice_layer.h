// insitu/views/slice_layer.h - a slice's settings and its values on a render step, for every
// view that shows one: the `slice` kind draws it as its own 2D image with axes in world units
// (insitu/views/slice_view.h); the 3D kinds place it in their picture with their `slice` key,
// where the plane lies nearer than what they drew (a depth composite).
//
// Reads: every owned particle the solver passes (positions, the quantity, mass and density),
// the fluid's box (the automatic plane origin and extent). In an MPI job every rank sums its
// owned particles' part and rank 0 holds the sum of all (exact), which it draws.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "insitu/config/settings.h"
#include "insitu/views/color_map.h"
#include "insitu/views/legend.h"
#include "insitu/views/sph_slice.h"
#include "insitu/views/view_framing.h"
#include "insitu/views/view_products.h"
#include "render/camera.h"
#include "render/float_image.h"
#include "render/recorder.h"
#include "voxspan/adapter.h"

namespace voxspan {

class Communicator;

// A slice's two passes in every view that shows one: the sums (collective under MPI) and the
// drawing.
namespace pass {
inline constexpr StatName slice_sum{"slice_sum"};
inline constexpr StatName slice_draw{"slice_draw"};
}  // namespace pass

struct SlicePlaneConfig {
  std::optional<Vec3d> origin;  // nullopt = the centre of the fluid's box
  Vec3d normal{0, 1, 0};
  bool operator==(const SlicePlaneConfig&) const = default;
};

// What a slice shows and how: the keys of a `slice` view, and of a 3D view's `slice` map.
struct SliceField {
  std::string quantity;  // the attribute interpolated (a vector: its magnitude); empty: none
  SphKernel kernel = SphKernel::cubic_spline;
  std::optional<double> smoothing_length;  // h, world units; nullopt = 1.3 spacings
  bool shepard = false;
  std::string mass = "mass", density = "density";
  std::string smoothing_attribute;  // h per particle; empty: smoothing_length for all
  SlicePlaneConfig plane;
  std::optional<double> extent;  // the plane's width, world units; nullopt = fit the fluid
  ColorMap color_map = ColorMap::viridis;
  std::string units;                           // after the colour bar's title; empty: none
  std::optional<std::array<double, 2>> range;  // nullopt = the step's min and max
  ColorScale scale = ColorScale::linear;
  int isolines = 8;
  bool operator==(const SliceField&) const = default;
};

// A particles view's `slice`: a SliceField placed in the view; with `cut`, the particles whose
// spheres reach the camera's side of the plane are not drawn, so that it shows inside the fluid.
struct ParticleSlice : SliceField {
  bool cut = true;
  bool operator==(const ParticleSlice&) const = default;
};

// The keys of a SliceField, and the check that a given one names its quantity.
std::vector<schema::Key<SliceField>> slice_field_keys();
void check_slice_field(yaml::MapReader& r, const SliceField& f);
const schema::Section<SlicePlaneConfig>& slice_plane_section();

class SliceLayer {
 public:
  // `key`: the key path of the field's keys in messages ("run.yaml:4:5: views[1].slice").
  // Throws voxspan::Error when smoothing_length is `auto` and the spacing is unknown.
  SliceLayer(const SliceField& field, std::string view_name, std::string key, double spacing,
             Communicator* comm);

  // The step's slice on a width x height grid of the plane (fitted to the fluid's box when the
  // settings leave the origin or the extent `auto`, clear of the `legend` margins; `up` orients
  // it). `flat_axis` >= 0: the particles lie in a plane across it (a 2D run), summed with the
  // 2D kernel. Collective in an MPI job: every rank calls it, and all throw when any failed. On
  // the root, a plane that reaches no particle is counted and warned about.
  void interpolate(const ParticleView& particles, const Bounds& fluid_box, int flat_axis,
                   glm::dvec3 up, std::int64_t step, int width, int height,
                   const LegendMargins& legend = {});

  // The slice as its own image: the colour-mapped values, isolines darkened, no-fluid pixels
  // dark, the colour bar at the right edge and the axes in world units at the bottom and left.
  void draw_image(FloatImage& picture) const;
  // Places the plane in a 3D picture: where a pixel's ray meets it at a point some particle
  // reaches, nearer than `view_depth` (view z per pixel, 0: nothing drawn), the pixel shows the
  // slice's colour and its depth becomes the plane's. The colour bar goes to `bar_side`.
  void draw_in_view(const Camera& camera, std::span<float> view_depth, FloatImage& picture,
                    BarSide bar_side) const;
  // The raw values and the plane's pixel-to-world mapping, for the EXR output.
  void fill_field(FieldImage& f) const;

  const SlicePlane& plane() const { return plane_; }
  const SliceImage& values() const { return values_; }
  ColorAxis axis() const;  // the colour map's on this step
  std::int64_t misses() const { return misses_; }
  // What draw_in_view's colour bar at `side` covers in a width x height picture.
  LegendMargins bar_margins(int width, int height, BarSide side) const {
    return color_bar_margins(width, height, side);
  }

 private:
  glm::vec3 colour(std::size_t k, const ColorAxis& axis) const;
  void sum_ranks(const ParticleView& particles, const SliceQuantity& q, int width, int height);

  const SliceField field_;
  const std::string bar_title_;
  const std::string view_name_;
  const std::string quantity_key_;
  const double spacing_;
  Communicator* const comm_;  // null in one process
  const ViewColorAxis color_axis_;
  SlicePlane plane_;
  SliceImage values_;
  std::int64_t misses_ = 0;
  bool told_not_finite_ = false;
};

}  // namespace voxspan
