#include "insitu/views/view_framing.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/glm.hpp>

namespace voxspan {
namespace {

glm::dvec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

constexpr double kPi = 3.14159265358979323846;

}  // namespace

void Bounds::add(const Bounds& o) {
  for (int a = 0; a < 3; ++a) {
    lo[std::size_t(a)] = std::min(lo[std::size_t(a)], o.lo[std::size_t(a)]);
    hi[std::size_t(a)] = std::max(hi[std::size_t(a)], o.hi[std::size_t(a)]);
  }
}

void Bounds::move(const std::array<double, 3>& by) {
  if (empty()) return;
  for (std::size_t a = 0; a < 3; ++a) lo[a] += by[a], hi[a] += by[a];
}

Bounds Bounds::of_spheres(std::span<const ParticleSphere> spheres) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, spheres.size(), 16384), Bounds{},
      [&](const tbb::blocked_range<std::size_t>& range, Bounds b) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const ParticleSphere& s = spheres[i];
          if (!(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z) &&
                std::isfinite(s.radius) && s.radius > 0))
            continue;
          const double c[3] = {s.x, s.y, s.z};
          for (std::size_t a = 0; a < 3; ++a) {
            b.lo[a] = std::min(b.lo[a], c[a] - s.radius);
            b.hi[a] = std::max(b.hi[a], c[a] + s.radius);
          }
        }
        return b;
      },
      [](Bounds a, const Bounds& b) {
        a.add(b);
        return a;
      });
}

namespace {

bool valid(const ParticleSphere& s) {
  return std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z) &&
         std::isfinite(s.radius) && s.radius > 0;
}

// The bin of coordinate c on an axis of `bins` bins from lo, each `width` wide (0: one bin).
std::size_t bin_of(double c, double lo, double width, int bins) {
  if (!(width > 0)) return 0;
  const double t = std::floor((c - lo) / width);
  return std::size_t(std::clamp(t, 0.0, double(bins - 1)));
}

}  // namespace

BulkBox::Range BulkBox::range(std::span<const ParticleSphere> spheres) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, spheres.size(), 16384), Range{},
      [&](const tbb::blocked_range<std::size_t>& r, Range out) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const ParticleSphere& s = spheres[i];
          if (!valid(s)) continue;
          const double c[3] = {s.x, s.y, s.z};
          for (std::size_t a = 0; a < 3; ++a) {
            out.centres.lo[a] = std::min(out.centres.lo[a], c[a]);
            out.centres.hi[a] = std::max(out.centres.hi[a], c[a]);
          }
          out.count_and_radii[0] += 1;
          out.count_and_radii[1] += s.radius;
        }
        return out;
      },
      [](Range a, const Range& b) {
        a.centres.add(b.centres);
        a.count_and_radii[0] += b.count_and_radii[0];
        a.count_and_radii[1] += b.count_and_radii[1];
        return a;
      });
}

void BulkBox::histogram(std::span<const ParticleSphere> spheres, const Range& range,
                        std::vector<std::int64_t>& scratch, std::vector<std::int64_t>& bins) {
  constexpr std::size_t kAxisBins = std::size_t(kBulkBins), kAll = 3 * kAxisBins;
  scratch.assign(kBulkChunks * kAll, 0);
  bins.assign(kAll, 0);
  if (range.centres.empty()) return;
  double width[3];
  for (std::size_t a = 0; a < 3; ++a)
    width[a] = (range.centres.hi[a] - range.centres.lo[a]) / kBulkBins;
  const std::size_t per_chunk = (spheres.size() + kBulkChunks - 1) / kBulkChunks;
  tbb::parallel_for(std::size_t(0), kBulkChunks, [&](std::size_t chunk) {
    std::int64_t* own = scratch.data() + chunk * kAll;
    const std::size_t end = std::min(spheres.size(), (chunk + 1) * per_chunk);
    for (std::size_t i = chunk * per_chunk; i < end; ++i) {
      const ParticleSphere& s = spheres[i];
      if (!valid(s)) continue;
      const double c[3] = {s.x, s.y, s.z};
      for (std::size_t a = 0; a < 3; ++a)
        ++own[a * kAxisBins + bin_of(c[a], range.centres.lo[a], width[a], kBulkBins)];
    }
  });
  for (std::size_t chunk = 0; chunk < kBulkChunks; ++chunk)
    for (std::size_t k = 0; k < kAll; ++k) bins[k] += scratch[chunk * kAll + k];
}

Bounds BulkBox::kept(const Range& range, std::span<const std::int64_t> bins) {
  Bounds out = range.centres;
  const double count = range.count_and_radii[0];
  if (range.centres.empty() || count <= 0) return out;
  const double diameter = 2 * range.count_and_radii[1] / count;
  const double least = kStrayShare * count;  // a body with fewer spheres is strays
  for (std::size_t a = 0; a < 3; ++a) {
    const double lo = range.centres.lo[a], width = (range.centres.hi[a] - lo) / kBulkBins;
    if (!(width > 0)) continue;
    const double gap_bins = std::ceil(kBulkGapDiameters * diameter / width);
    const std::int64_t gap = gap_bins > kBulkBins ? kBulkBins + 1 : std::int64_t(gap_bins);
    const std::span<const std::int64_t> axis = bins.subspan(a * kBulkBins, kBulkBins);
    // Walk the bodies (runs of nonempty bins with gaps under `gap`); keep from the first one
    // that is not strays to the last.
    int first_kept = -1, last_kept = -1, start = -1, last = -1;
    std::int64_t held = 0;
    auto close = [&] {
      if (start >= 0 && double(held) >= least) {
        if (first_kept < 0) first_kept = start;
        last_kept = last;
      }
    };
    for (int k = 0; k < kBulkBins; ++k) {
      if (axis[std::size_t(k)] == 0) continue;
      if (start < 0 || k - last > gap) {
        close();
        start = k;
        held = 0;
      }
      held += axis[std::size_t(k)];
      last = k;
    }
    close();
    if (first_kept < 0) continue;  // no body holds enough: keep everything
    if (first_kept > 0) out.lo[a] = lo + first_kept * width;
    if (last_kept < kBulkBins - 1) out.hi[a] = lo + (last_kept + 1) * width;
  }
  return out;
}

BulkBox::Split BulkBox::split(std::span<const ParticleSphere> spheres, const Bounds& kept) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, spheres.size(), 16384), Split{},
      [&](const tbb::blocked_range<std::size_t>& r, Split out) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const ParticleSphere& s = spheres[i];
          if (!valid(s)) continue;
          const double c[3] = {s.x, s.y, s.z};
          bool inside = true;
          for (std::size_t a = 0; a < 3; ++a)
            inside = inside && c[a] >= kept.lo[a] && c[a] <= kept.hi[a];
          Bounds& to = inside ? out.box : out.left_out_box;
          const double r_add = inside ? double(s.radius) : 0.0;
          for (std::size_t a = 0; a < 3; ++a) {
            to.lo[a] = std::min(to.lo[a], c[a] - r_add);
            to.hi[a] = std::max(to.hi[a], c[a] + r_add);
          }
          out.left_out += inside ? 0 : 1;
        }
        return out;
      },
      [](Split a, const Split& b) {
        a.box.add(b.box);
        a.left_out_box.add(b.left_out_box);
        a.left_out += b.left_out;
        return a;
      });
}

BulkBox::Split bulk_box(std::span<const ParticleSphere> spheres) {
  const BulkBox::Range range = BulkBox::range(spheres);
  std::vector<std::int64_t> scratch, bins;
  BulkBox::histogram(spheres, range, scratch, bins);
  return BulkBox::split(spheres, BulkBox::kept(range, bins));
}

int flat_axis(const Bounds& centres) {
  if (centres.empty()) return -1;
  double largest = 0;
  for (std::size_t a = 0; a < 3; ++a) largest = std::max(largest, centres.hi[a] - centres.lo[a]);
  // Equal to rounding: a 2D solver writes the same number (usually 0) for every particle. One
  // such axis only: a line of particles is no plane to face.
  int flat = -1, count = 0;
  for (std::size_t a = 0; a < 3; ++a)
    if (largest > 0 && centres.hi[a] - centres.lo[a] <= 1e-9 * largest) flat = int(a), ++count;
  return count == 1 ? flat : -1;
}

namespace {

// A 2D fluid's plane seen head-on, from the side the default direction looks from, with the
// plane's upward axis up: y in the x-y plane (PySPH's 2D runs, gravity along -y), z in the
// others (DualSPHysics' x-z plane). Direction and up: the view's where it gives either.
std::pair<glm::dvec3, glm::dvec3> head_on_orientation(const CameraConfig& c, int flat) {
  const CameraConfig defaults;
  if (flat < 0 || c.direction != defaults.direction || c.up != defaults.up)
    return {glm::normalize(vec(c.direction)), vec(c.up)};
  glm::dvec3 forward(0), up(0, 0, 1);
  forward[flat] = defaults.direction[std::size_t(flat)] > 0 ? 1 : -1;
  if (flat == 2) up = glm::dvec3(0, 1, 0);
  return {forward, up};
}

}  // namespace

Camera frame_camera(const ViewSettings& view, const Bounds& box) {
  return frame_camera(view.camera, view.width, view.height, box);
}

Camera frame_camera(const CameraConfig& c, int width, int height, const Bounds& box,
                    const LegendMargins& clear, int flat) {
  Camera camera;
  camera.up = vec(c.up);
  camera.fov_y_degrees = c.fov_degrees;
  camera.width = width;
  camera.height = height;
  if (!c.automatic) {
    camera.eye = vec(c.eye);
    camera.target = vec(c.target);
    return camera;
  }
  const auto [forward, up_axis] = head_on_orientation(c, flat);
  camera.up = up_axis;
  if (box.empty()) {
    camera.target = glm::dvec3(0);
    camera.eye = -forward;
    return camera;
  }
  const glm::dvec3 lo(box.lo[0], box.lo[1], box.lo[2]), hi(box.hi[0], box.hi[1], box.hi[2]);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_y = std::tan(0.5 * c.fov_degrees * kPi / 180.0);
  const double tan_x = tan_y * double(width) / double(height);
  // The space between the margins at depth 1: centred at (mid_x, mid_y), half extents
  // (half_x, half_y) (at no margins (0, 0) and (tan_x, tan_y)).
  const double per_x = 2 * tan_x / double(width), per_y = 2 * tan_y / double(height);
  const double mid_x = 0.5 * per_x * double(clear.left - clear.right);
  const double mid_y = 0.5 * per_y * double(clear.bottom - clear.top);
  const double half_x = tan_x - 0.5 * per_x * double(clear.left + clear.right);
  const double half_y = tan_y - 0.5 * per_y * double(clear.bottom + clear.top);
  // The box's centre seen at (mid_x, mid_y): the eye at centre - dist (forward + mid_x right +
  // mid_y up). A corner p (relative to the centre) is then at depth dist + p.forward, and inside
  // the space when |p.right - mid_x p.forward| <= half_x depth (and so for up): the distance is
  // the largest bound.
  const glm::dvec3 half = 0.5 * (hi - lo) * c.margin;
  double dist = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? half.x : -half.x, (corner & 2) ? half.y : -half.y,
                       (corner & 4) ? half.z : -half.z);
    const double depth_offset = glm::dot(p, forward);
    dist =
        std::max(dist, std::abs(glm::dot(p, right) - mid_x * depth_offset) / half_x - depth_offset);
    dist = std::max(dist, std::abs(glm::dot(p, up) - mid_y * depth_offset) / half_y - depth_offset);
  }
  // A box of zero size (one particle of radius 0 never gets here) still needs a distance; no
  // floor otherwise, in world units or relative to the origin: a 2e-9 m block was a dot.
  if (!(dist > 0)) dist = 1e-6 * std::max(1.0, glm::length(centre));
  camera.target = centre - dist * (mid_x * right + mid_y * up);
  camera.eye = camera.target - dist * forward;
  return camera;
}

Camera ViewFraming::update(std::span<const ParticleSphere> boundary) {
  return update(Bounds::of_spheres(boundary));
}

namespace {

double largest_side(const Bounds& b) {
  return b.empty() ? 0 : std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
}

}  // namespace

glm::dvec3 ViewFraming::pivot() const {
  if (!camera_.automatic) return vec(camera_.target);
  if (box_.empty()) return glm::dvec3(0);  // where frame_camera looks then
  return 0.5 * (glm::dvec3(box_.lo[0], box_.lo[1], box_.lo[2]) +
                glm::dvec3(box_.hi[0], box_.hi[1], box_.hi[2]));
}

Camera ViewFraming::update(const Bounds& now, int flat) {
  const double before = largest_side(box_);
  if (!camera_.bounds.empty()) {  // the user's box, whatever the fluid does
    for (std::size_t a = 0; a < 3; ++a) {
      box_.lo[a] = camera_.bounds[a][0];
      box_.hi[a] = camera_.bounds[a][1];
    }
  } else if (camera_.framing != Framing::first || box_.empty()) {
    // A manual camera keeps the box too: the environment's ground lies under it.
    if (camera_.framing == Framing::grow) box_.add(now);
    else if (!now.empty()) box_ = now;
  }
  jumped_ = camera_.automatic && before > 0 && largest_side(box_) > 4 * before;
  return frame_camera(camera_, width_, height_, box_, clear_, flat);
}

void distances_from_view_depth(const Camera& camera, std::span<const float> view_depth,
                               FloatImage& distances) {
  if (distances.width != camera.width || distances.height != camera.height)
    distances = FloatImage(camera.width, camera.height);
  const ViewFrame f(camera);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t k = std::size_t(x) + std::size_t(camera.width) * std::size_t(y);
      distances.set(x, y, glm::vec4(float(double(view_depth[k]) * f.ray_scale(x, y)), 0, 0, 0));
    }
}

void view_depth_from_distances(const Camera& camera, const FloatImage& distances,
                               std::vector<float>& view_depth) {
  const ViewFrame f(camera);
  view_depth.resize(std::size_t(distances.width) * std::size_t(distances.height));
  for (int y = 0; y < distances.height; ++y)
    for (int x = 0; x < distances.width; ++x)
      view_depth[std::size_t(x) + std::size_t(distances.width) * std::size_t(y)] =
          float(double(distances.at(x, y).r) / f.ray_scale(x, y));
}

}  // namespace voxspan
