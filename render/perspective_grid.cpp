#include "render/perspective_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "voxspan/error.h"

namespace voxspan {
namespace {

bool finite_sphere(const ParticleSphere& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
         std::isfinite(p.radius) && p.radius > 0;
}

// Footprints reach this far (pixels) past the exact silhouette, so that the GPU's float
// evaluation of the same rule stays conservative.
constexpr double kPixelMargin = 0.01;

int clamp_floor(double v, int lo, int hi) {
  return static_cast<int>(std::clamp(std::floor(v), double(lo), double(hi)));
}
int clamp_ceil(double v, int lo, int hi) {
  return static_cast<int>(std::clamp(std::ceil(v), double(lo), double(hi)));
}

}  // namespace

void validate(const GridOptions& o) {
  if (!(o.alpha_degrees > 0 && o.alpha_degrees < 90))
    throw make_error("grid alpha_degrees = ", o.alpha_degrees, " is outside (0, 90)");
  if (o.max_layers < 32 || o.max_layers % 32 != 0)
    throw make_error("grid max_layers = ", o.max_layers, " is not a positive multiple of 32");
  if (!(o.min_near >= 0) || !std::isfinite(o.min_near))
    throw make_error("grid min_near = ", o.min_near, " is not a finite number >= 0");
  if (!(o.min_near_fraction >= 0 && o.min_near_fraction < 1))
    throw make_error("grid min_near_fraction = ", o.min_near_fraction, " is outside [0, 1)");
  if (o.min_near == 0 && o.min_near_fraction == 0)
    throw make_error(
        "grid min_near and min_near_fraction are both 0: the near plane needs a floor");
}

PerspectiveGrid PerspectiveGrid::with_frame(const Camera& camera, const GridOptions& options) {
  validate(options);
  PerspectiveGrid g;
  g.camera_ = camera;
  g.view_ = ViewFrame(camera);
  g.alpha_degrees_ = options.alpha_degrees;
  return g;
}

PerspectiveGrid PerspectiveGrid::over(const Camera& camera, double near, double far,
                                      const GridOptions& options) {
  if (!(near > 0 && far > near && std::isfinite(far)))
    throw make_error("grid depth range [", near, ", ", far, "] is not 0 < near < far");
  PerspectiveGrid g = with_frame(camera, options);
  g.set_depth_range(near, far, options);
  return g;
}

PerspectiveGrid PerspectiveGrid::rescaled(const Camera& camera, double factor) const {
  PerspectiveGrid g = *this;
  g.camera_ = camera;
  g.view_ = ViewFrame(camera);
  g.near_ *= factor;
  g.far_ *= factor;
  return g;
}

void PerspectiveGrid::set_depth_range(double near, double far, const GridOptions& options) {
  near_ = near;
  far_ = far;
  // Sec. 4.2: c_d = c_w tan(alpha) with c_w = 2 tan(fov_y / 2) / R_y * d, so c_d = K_d d.
  k_d_ = std::tan(options.alpha_degrees * std::numbers::pi / 180) * 2 * view_.tan_half_y /
         view_.height;
  const double needed = std::ceil(std::log(far / near) / std::log1p(k_d_));
  layers_needed_ = static_cast<int>(std::min(needed, 1e9));
  layers_ = std::max(32, (std::max(layers_needed_, 1) + 31) / 32 * 32);
  layer_cap_hit_ = layers_ > options.max_layers;
  if (layer_cap_hit_) {
    // Fewer layers over the same depth range: each layer grows, and alpha with it.
    layers_ = options.max_layers;
    k_d_ = std::expm1(std::log(far / near) / layers_);
    alpha_degrees_ =
        std::atan(k_d_ * view_.height / (2 * view_.tan_half_y)) * 180 / std::numbers::pi;
  }
  log2_step_ = std::log2(1 + k_d_);
}

// Classifies every particle; spheres in the frustum that end before depth `floor` count as
// behind, the others set the depth range.
DepthRange PerspectiveGrid::survey(std::span<const ParticleSphere> particles, double floor) const {
  using Range = tbb::blocked_range<std::size_t>;
  return tbb::parallel_reduce(
      Range(0, particles.size(), 4096), DepthRange{},
      [&](const Range& r, DepthRange d) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const ParticleSphere& p = particles[i];
          if (!finite_sphere(p)) {
            ++d.counts.invalid;
            continue;
          }
          const glm::dvec3 c = view_.to_view(glm::dvec3(p.x, p.y, p.z));
          if (c.z + p.radius <= std::max(floor, 0.0)) {
            ++d.counts.behind;
          } else if (!view_.meets_pyramid(c, p.radius)) {
            ++d.counts.outside;
          } else {
            ++d.counts.visible;
            d.lo = std::min(d.lo, c.z - p.radius);
            d.hi = std::max(d.hi, c.z + p.radius);
          }
        }
        return d;
      },
      [](DepthRange a, const DepthRange& b) {
        a.lo = std::min(a.lo, b.lo);
        a.hi = std::max(a.hi, b.hi);
        a.counts.visible += b.counts.visible;
        a.counts.invalid += b.counts.invalid;
        a.counts.behind += b.counts.behind;
        a.counts.outside += b.counts.outside;
        return a;
      });
}

PerspectiveGrid PerspectiveGrid::fit(const Camera& camera,
                                     std::span<const ParticleSphere> particles,
                                     const GridOptions& options, CullCounts* counts,
                                     const DepthRangeCombine& combine) {
  PerspectiveGrid g = with_frame(camera, options);
  const auto global = [&](const DepthRange& local) { return combine ? combine(local) : local; };
  DepthRange range = g.survey(particles, 0);
  DepthRange all = global(range);
  // The near floor depends on the far depth. Only when some sphere starts before it does a
  // second pass sort out those that end before it (usually none do: one pass).
  const double near_floor = std::max(options.min_near, options.min_near_fraction * all.hi);
  if (all.counts.visible > 0 && all.lo < near_floor) {
    range = g.survey(particles, near_floor);
    all = global(range);
  }
  if (counts != nullptr) *counts = range.counts;
  if (all.counts.visible > 0) g.set_depth_range(std::max(near_floor, all.lo), all.hi, options);
  return g;
}

double PerspectiveGrid::layer_depth(double i) const { return near_ * std::exp2(i * log2_step_); }

double PerspectiveGrid::layer_of(double depth) const {
  return std::log2(depth / near_) / log2_step_;
}

double PerspectiveGrid::layer_thickness(double depth) const {
  const double i = std::clamp(std::floor(layer_of(depth)), 0.0, double(std::max(layers_ - 1, 0)));
  return layer_depth(i) * k_d_;
}

PixelRect PerspectiveGrid::sphere_pixels(glm::dvec3 c, double r) const {
  const ViewFrame& v = view_;
  if (!v.meets_pyramid(c, r)) return {};
  if (c.z - r <= 0) return {0, 0, v.width - 1, v.height - 1};
  // Exact silhouette slopes x / z (and y / z): the tangents from the eye to the disk the sphere
  // projects to in the xz (yz) plane, tan(atan t -+ atan u) with t = a / z and u = r / s, s the
  // tangent's length; multiplied through by z s, (a s -+ r z) / (z s +- a r). Then
  // ViewFrame::pixel_x (pixel_y) of them, its division by tan_half folded into the slopes' one
  // division per axis: every sphere of a frame comes through here, and divisions were most of
  // its cost (9 before, 2 now: docs/benchmarks.md, "Tiles of 32 pixels").
  const auto pixel_range = [&](double a, double tan_half, int size, double& lo, double& hi) {
    const double s = std::sqrt(a * a + c.z * c.z - r * r);
    const double den_lo = c.z * s + a * r, den_hi = c.z * s - a * r;  // > 0: c.z > r
    const double scale = 0.5 * size / (tan_half * den_lo * den_hi);
    lo = (a * s - r * c.z) * den_hi * scale + 0.5 * size - 0.5;
    hi = (a * s + r * c.z) * den_lo * scale + 0.5 * size - 0.5;
  };
  double fx0, fx1, fy0, fy1;
  pixel_range(c.x, v.tan_half_x, v.width, fx0, fx1);
  // Rows grow downwards: the top of the sphere (largest y) has the smallest row.
  pixel_range(-c.y, v.tan_half_y, v.height, fy0, fy1);
  if (fx1 < -kPixelMargin || fx0 > v.width - 1 + kPixelMargin || fy1 < -kPixelMargin ||
      fy0 > v.height - 1 + kPixelMargin)
    return {};
  // The pixels whose centres lie inside, with a margin for the GPU's float rounding.
  PixelRect rect{clamp_ceil(fx0 - kPixelMargin, 0, v.width - 1),
                 clamp_ceil(fy0 - kPixelMargin, 0, v.height - 1),
                 clamp_floor(fx1 + kPixelMargin, 0, v.width - 1),
                 clamp_floor(fy1 + kPixelMargin, 0, v.height - 1)};
  return rect;
}

}  // namespace voxspan
