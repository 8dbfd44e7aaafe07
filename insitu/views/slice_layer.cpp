#include "insitu/views/slice_layer.h"

#include <algorithm>
#include <utility>
#include <cmath>
#include <limits>

#include "insitu/parallel/communicator.h"
#include "insitu/views/view_keys.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

glm::dvec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

// The plane's rectangle for this step: the settings, or fitted around the fluid's box grown by
// `reach` (where the sums still reach) with `legend`'s margins left clear (an automatic extent
// moves the picture's centre off the fluid's by half the difference of opposite margins).
SlicePlane plane_for(const SliceField& s, const Bounds& box, double reach, glm::dvec3 up, int width,
                     int height, const LegendMargins& legend) {
  const bool have_box = !box.empty();
  const glm::dvec3 lo = have_box ? vec(box.lo) - reach : glm::dvec3(-0.5);
  const glm::dvec3 hi = have_box ? vec(box.hi) + reach : glm::dvec3(0.5);
  const glm::dvec3 origin = s.plane.origin ? vec(*s.plane.origin) : 0.5 * (lo + hi);
  const double aspect = double(width) / double(height);
  SlicePlane p = SlicePlane::make(origin, vec(s.plane.normal), 1, 1, up);
  double w = s.extent.value_or(0);
  if (!s.extent) {
    double su = 0, sv = 0;  // the box's half extents along u and v, around the origin
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
      su = std::max(su, std::abs(glm::dot(corner - origin, p.u)));
      sv = std::max(sv, std::abs(glm::dot(corner - origin, p.v)));
    }
    // World units a pixel, so that the box with 5 % to spare fits the data's own region.
    const double free_w = double(width - legend.left - legend.right);
    const double free_h = double(height - legend.top - legend.bottom);
    const double per_pixel = 2.1 * std::max({su / free_w, sv / free_h, 1e-300});
    w = per_pixel * width;
    p.origin -= 0.5 * double(legend.left - legend.right) * per_pixel * p.u;
    p.origin += 0.5 * double(legend.top - legend.bottom) * per_pixel * p.v;
  }
  p.width = w;
  p.height = w / aspect;
  return p;
}

// The axis of a picture edge along `dir` (unit), `length` long around `origin`: the world
// coordinate when `dir` is a coordinate axis ("x" with the plane's normal along y), else the
// distance from the origin along it ("u").
Axis axis_along(glm::dvec3 origin, glm::dvec3 dir, double length, std::string_view other) {
  static constexpr std::string_view kNames[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    if (std::abs(dir[k]) > 1 - 1e-12)
      return {origin[k] - 0.5 * length * dir[k], origin[k] + 0.5 * length * dir[k], kNames[k]};
  return {-0.5 * length, 0.5 * length, other};
}

}  // namespace

const schema::Section<SlicePlaneConfig>& slice_plane_section() {
  using P = SlicePlaneConfig;
  static const schema::Section<P> s{
      "views[i].plane",
      {schema::vec3_or_auto("origin", &P::origin,
                            "a point of the plane; `auto` = the centre of the fluid's box"),
       schema::vec3("normal", &P::normal, "the plane's normal (any length but 0)")},
      [](yaml::MapReader& r, P& p) {
        if (r.has("normal") && !(glm::length(vec(p.normal)) > 0))
          r.checker().error(r.find("normal"), r.path("normal"), "must not be zero");
      }};
  return s;
}

std::vector<schema::Key<SliceField>> slice_field_keys() {
  using S = SliceField;
  return schema::joined(
      sph_sum_keys<S>(
          "the particle attribute interpolated on the plane (a vector: its magnitude); required",
          "divide by the sum of (m / rho) W: a uniform field stays flat up to the free surface"),
      std::vector<schema::Key<S>>{
          schema::map<S, SlicePlaneConfig>("plane", &S::plane, slice_plane_section(),
                                           "the plane: `origin` and `normal`"),
          schema::number_or_auto("extent", &S::extent, schema::above(0),
                                 "the plane's width, world units (the height follows the "
                                 "picture's aspect); `auto` = the fluid's box as the plane "
                                 "sees it")},
      color_map_keys<S>("the colour map",
                        "the step's smallest and largest, on a `log` scale without `shepard` "
                        "those of the pixels at least half inside the fluid"),
      std::vector<schema::Key<S>>{schema::integer(
          "isolines", &S::isolines, 0, 64, "isolines, evenly spaced inside the range; 0: none")});
}

void check_slice_field(yaml::MapReader& r, const SliceField& f) {
  check_color_axis(r, f);
  check_sph_sum(r, f);
  if (f.quantity.empty())
    r.checker().error(r.node(), r.path("quantity"),
                      "a slice needs `quantity` (the attribute it shows)");
}

SliceLayer::SliceLayer(const SliceField& field, std::string view_name, std::string key,
                       double spacing, Communicator* comm)
    : field_(field),
      bar_title_(color_bar_title(field.quantity, field.units)),
      view_name_(std::move(view_name)),
      quantity_key_(key.empty() ? "quantity" : key + ".quantity"),
      spacing_(spacing),
      comm_(comm),
      color_axis_(view_name_, field.quantity, comm == nullptr || comm->root()) {
  if (!field.smoothing_length && !(spacing > 0))
    throw make_error("view ", view_name_,
                     ": smoothing_length is `auto` but the particle spacing is unknown; set it");
  if (comm == nullptr || comm->root())
    warn_of_odd_smoothing("view " + view_name_ + ": smoothing_length", field.smoothing_length,
                          spacing);
}

void SliceLayer::interpolate(const ParticleView& particles, const Bounds& fluid_box, int flat_axis,
                             glm::dvec3 up, std::int64_t step, int width, int height,
                             const LegendMargins& legend) {
  // With a legend to keep clear (a slice view's own picture) the sums' whole reach is fitted,
  // so that no value lies under it; a plane in a 3D view keeps the box's size.
  const double h = field_.smoothing_length.value_or(kAutoSmoothingFactor * spacing_);
  plane_ = plane_for(field_, fluid_box, legend.right > 0 ? kernel_support(field_.kernel) * h : 0,
                     up, width, height, legend);
  SliceQuantity q;
  q.name = field_.quantity;
  q.key = quantity_key_;
  q.mass = field_.mass;
  q.density = field_.density;
  // A run in a plane (its particles flat along one axis) sums with the 2D kernel, over areas.
  q.dimensions = flat_axis >= 0 ? 2 : 3;
  q.rest_volume = q.dimensions == 2 ? spacing_ * spacing_ : spacing_ * spacing_ * spacing_;
  q.kernel = field_.kernel;
  q.smoothing_length = field_.smoothing_length.value_or(kAutoSmoothingFactor * spacing_);
  q.smoothing = field_.smoothing_attribute;
  q.shepard = field_.shepard;
  sum_ranks(particles, q, width, height);
  // Each rank says its own (its lines name it): the sums left them out, which dips the field.
  if (values_.values_not_finite > 0 && !std::exchange(told_not_finite_, true))
    log_warning("view ", view_name_, ": step ", step, ": ", values_.values_not_finite,
                " particles near the plane whose ", field_.quantity,
                " is NaN or infinite are left out of the sums (said once)");
  if ((comm_ == nullptr || comm_->root()) && values_.pixels_reached == 0) {
    ++misses_;
    log_warning("view ", view_name_, ": step ", step, ": the slice plane reaches no particle (",
                misses_, " steps so far)");
  }
}

// The slice of this process's owned particles; in an MPI job the sum over every rank's (exact:
// each particle counts on one rank). Every rank takes part in the sums even when its own part
// failed, then all throw, naming the failure, so that none waits for another.
void SliceLayer::sum_ranks(const ParticleView& particles, const SliceQuantity& q, int width,
                           int height) {
  std::string failure;
  try {
    interpolate_slice(particles, q, plane_, width, height, values_);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  if (comm_ == nullptr) {
    if (!failure.empty()) throw Error(failure);
    return;
  }
  comm_->agree_or_throw(failure.empty(), failure);
  comm_->sum(values_.sum);
  comm_->sum(values_.weight);
  finish_slice(values_, q.shepard);
}

// On a log scale the raw sum's tail at the fluid's edge (1e-11 of the bulk where a kernel's
// support ends) would set the range's low end and leave the fluid one colour: there the range
// comes from the pixels at least half inside the fluid (their kernel weight, the SPH free
// surface's usual level, at least 0.5), where any are.
ColorAxis SliceLayer::axis() const {
  const bool tail = field_.scale == ColorScale::log && !field_.shepard;
  ValueSpan seen, inside;
  for (std::size_t k = 0; k < values_.values.size(); ++k) {
    if (values_.weight[k] > 0) seen.add(values_.values[k]);
    if (tail && values_.weight[k] >= 0.5) inside.add(values_.values[k]);
  }
  return color_axis_(field_.range, inside.lo <= inside.hi ? inside : seen, field_.scale);
}

// The colour of plane pixel k (which a particle reaches): the map, darkened on an isoline (a
// pixel whose level differs from its right or lower neighbour's; evenly spaced along the axis,
// so a decade apart each on a log scale spanning as many). The range's ends are no isolines:
// the levels are clamped, or the pixels at the maximum of an automatic range would be ringed.
glm::vec3 SliceLayer::colour(std::size_t k, const ColorAxis& axis) const {
  const int w = values_.width, lines = field_.isolines;
  glm::vec3 c = map_color(field_.color_map, axis.t(values_.values[k]));
  if (lines == 0) return c;
  const auto level = [&](std::size_t n) {
    return std::clamp(std::floor(axis.t(values_.values[n]) * (lines + 1)), 0.0, double(lines));
  };
  const std::size_t i = k % std::size_t(w), j = k / std::size_t(w);
  const double mine = level(k);
  const bool edge = (i + 1 < std::size_t(w) && values_.weight[k + 1] > 0 && level(k + 1) != mine) ||
                    (j + 1 < std::size_t(values_.height) &&
                     values_.weight[k + std::size_t(w)] > 0 && level(k + std::size_t(w)) != mine);
  return edge ? c * 0.25f : c;
}

void SliceLayer::draw_image(FloatImage& picture) const {
  const int w = values_.width, h = values_.height;
  if (picture.width != w || picture.height != h) picture = FloatImage(w, h);
  const ColorAxis axis = this->axis();
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const std::size_t k = std::size_t(i) + std::size_t(w) * std::size_t(j);
      picture.set(i, j,
                  values_.weight[k] > 0 ? glm::vec4(colour(k, axis), 1.0f)
                                        : glm::vec4(0.02f, 0.02f, 0.025f, 1.0f));
    }
  draw_color_bar(picture, field_.color_map, axis, bar_title_);
  draw_axes(picture, axis_along(plane_.origin, plane_.u, plane_.width, "u"),
            axis_along(plane_.origin, plane_.v, plane_.height, "v"));
}

void SliceLayer::draw_in_view(const Camera& camera, std::span<float> view_depth,
                              FloatImage& picture, BarSide bar_side) const {
  const ViewFrame f(camera);
  const int w = values_.width, h = values_.height;
  const ColorAxis axis = this->axis();
  for (int y = 0; y < picture.height; ++y)
    for (int x = 0; x < picture.width; ++x) {
      const glm::dvec3 ray = f.world_ray(x, y);  // depth component 1
      const double along = glm::dot(plane_.normal, ray);
      if (along == 0) continue;  // the ray runs in the plane
      const double z = glm::dot(plane_.normal, plane_.origin - f.eye) / along;
      const std::size_t px = std::size_t(x) + std::size_t(picture.width) * std::size_t(y);
      if (!(z > 0) || (view_depth[px] > 0 && !(z < view_depth[px]))) continue;
      const glm::dvec3 d = f.eye + z * ray - plane_.origin;
      const double a = glm::dot(d, plane_.u) / plane_.width + 0.5;
      const double b = 0.5 - glm::dot(d, plane_.v) / plane_.height;
      if (!(a >= 0 && a < 1 && b >= 0 && b < 1)) continue;
      const std::size_t k = std::size_t(std::min(int(a * w), w - 1)) +
                            std::size_t(w) * std::size_t(std::min(int(b * h), h - 1));
      if (!(values_.weight[k] > 0)) continue;
      // A plane seen edge-on darkens a little, so that its tilt reads.
      const float lit = float(0.75 + 0.25 * std::abs(along) / glm::length(ray));
      picture.set(x, y, glm::vec4(colour(k, axis) * lit, 1.0f));
      view_depth[px] = float(z);
    }
  draw_color_bar(picture, field_.color_map, axis, bar_title_, bar_side);
}

void SliceLayer::fill_field(FieldImage& f) const {
  const int w = values_.width, h = values_.height;
  if (f.values.width != w || f.values.height != h) f.values = FloatImage(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const std::size_t k = std::size_t(i) + std::size_t(w) * std::size_t(j);
      f.values.set(i, j, glm::vec4(values_.values[k], float(values_.weight[k]), 0, 0));
    }
  f.quantity = field_.quantity;
  f.origin = plane_.origin, f.u = plane_.u, f.v = plane_.v;
  f.width = plane_.width, f.height = plane_.height;
}

}  // namespace voxspan
