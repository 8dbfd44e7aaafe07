#include "render/reference/exact_spans.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "render/cell_march.h"

namespace voxspan {
namespace {

constexpr int kBin = 8;  // screen bin side, pixels

struct Sphere {
  glm::dvec3 center;  // view space
  double radius;
};

struct Interval {
  double entry, exit;
  int entry_sphere = -1, exit_sphere = -1;  // the spheres the boundaries lie on; -1: none
};

// Spheres of the frame sorted into screen bins by their conservative pixel rectangles.
struct ScreenBins {
  int nx = 0, ny = 0;
  std::vector<std::uint32_t> start;  // nx * ny + 1
  std::vector<std::uint32_t> items;  // sphere indices
};

ScreenBins bin_spheres(const PerspectiveGrid& grid, const std::vector<Sphere>& spheres,
                       std::vector<PixelRect>& rects) {
  ScreenBins bins;
  bins.nx = (grid.width() + kBin - 1) / kBin;
  bins.ny = (grid.height() + kBin - 1) / kBin;
  bins.start.assign(static_cast<std::size_t>(bins.nx) * bins.ny + 1, 0);
  const auto each_bin = [&](const PixelRect& r, auto&& f) {
    if (r.empty()) return;
    for (int by = r.y0 / kBin; by <= r.y1 / kBin; ++by)
      for (int bx = r.x0 / kBin; bx <= r.x1 / kBin; ++bx)
        f(static_cast<std::size_t>(bx) + static_cast<std::size_t>(by) * bins.nx);
  };
  for (const PixelRect& r : rects) each_bin(r, [&](std::size_t b) { ++bins.start[b + 1]; });
  for (std::size_t b = 1; b < bins.start.size(); ++b) bins.start[b] += bins.start[b - 1];
  bins.items.resize(bins.start.back());
  std::vector<std::uint32_t> cursor(bins.start.begin(), bins.start.end() - 1);
  for (std::size_t i = 0; i < spheres.size(); ++i)
    each_bin(rects[i],
             [&](std::size_t b) { bins.items[cursor[b]++] = static_cast<std::uint32_t>(i); });
  return bins;
}

// Depth interval of the ray z * d (view space) inside a sphere; false when it misses or only
// touches. The closest-approach form keeps precision for small, distant spheres.
bool chord(glm::dvec3 d, const Sphere& s, Interval& out) {
  const double a = glm::dot(d, d);
  const double zc = glm::dot(d, s.center) / a;
  const glm::dvec3 perp = s.center - zc * d;
  const double h2 = s.radius * s.radius - glm::dot(perp, perp);
  if (!(h2 > 0)) return false;
  const double half = std::sqrt(h2 / a);
  out.entry = zc - half;
  out.exit = zc + half;
  return true;
}

// Outward world normal of sphere `index` at depth z on the view ray d; zero for no sphere.
glm::vec3 sphere_normal(const PerspectiveGrid& grid, const std::vector<Sphere>& spheres, int index,
                        glm::dvec3 d, double z) {
  if (index < 0) return glm::vec3(0.0f);
  const glm::dvec3 n = glm::normalize(d * z - spheres[static_cast<std::size_t>(index)].center);
  const ViewFrame& v = grid.view();
  return glm::vec3(n.x * v.right + n.y * v.up + n.z * v.forward);
}

// Hands each merged interval to `emit`.
template <class Emit>
void merge(std::vector<Interval>& intervals, double ray_scale, double gap, Emit&& emit) {
  std::sort(intervals.begin(), intervals.end(),
            [](const Interval& a, const Interval& b) { return a.entry < b.entry; });
  bool open = false;
  Interval cur{0, 0};
  for (const Interval& iv : intervals) {
    if (open && (iv.entry <= cur.exit || (iv.entry - cur.exit) * ray_scale < gap)) {
      if (iv.exit > cur.exit) cur.exit = iv.exit, cur.exit_sphere = iv.exit_sphere;
      continue;
    }
    if (open) emit(cur);
    cur = iv;
    open = true;
  }
  if (open) emit(cur);
}

}  // namespace

SpanImage exact_spans(const PerspectiveGrid& grid, std::span<const ParticleSphere> particles,
                      const CellStatesView& cells, const ReferenceOptions& options) {
  return exact_spans(grid, particles, cells, options, nullptr);
}

SpanImage exact_spans(const PerspectiveGrid& grid, std::span<const ParticleSphere> particles,
                      const CellStatesView& cells, const ReferenceOptions& options,
                      std::vector<SpanNormals>* normals) {
  SpanImage image;
  image.grid = grid;
  const int width = grid.width(), height = grid.height();
  image.pixels.assign(static_cast<std::size_t>(width) * height, PixelSpans{});
  if (normals != nullptr) normals->clear();
  if (grid.empty()) return image;

  std::vector<Sphere> spheres;
  std::vector<PixelRect> rects;
  for (const ParticleSphere& p : particles) {
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
          std::isfinite(p.radius) && p.radius > 0))
      continue;
    const Sphere s{grid.view().to_view(glm::dvec3(p.x, p.y, p.z)), p.radius};
    if (s.center.z + s.radius <= grid.near()) continue;
    const PixelRect r = grid.sphere_pixels(s.center, s.radius);
    if (r.empty()) continue;
    spheres.push_back(s);
    rects.push_back(r);
  }
  const ScreenBins bins = bin_spheres(grid, spheres, rects);
  const double near = grid.near(), far = grid.grid_far();

  // Rows in parallel, each into its own list; offsets are fixed up when they are joined.
  std::vector<std::vector<Span>> row_spans(static_cast<std::size_t>(height));
  std::vector<std::vector<SpanNormals>> row_normals(normals != nullptr ? row_spans.size() : 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    std::vector<Interval> intervals;
    for (int y = rows.begin(); y != rows.end(); ++y) {
      SpanListBuilder builder(row_spans[static_cast<std::size_t>(y)], options.max_spans);
      for (int x = 0; x < width; ++x) {
        const glm::dvec3 d = grid.view().view_ray(x, y);
        const double scale = glm::length(d);
        intervals.clear();
        const std::size_t bin =
            static_cast<std::size_t>(x / kBin) + static_cast<std::size_t>(y / kBin) * bins.nx;
        for (std::uint32_t k = bins.start[bin]; k < bins.start[bin + 1]; ++k) {
          Interval iv;
          if (!chord(d, spheres[bins.items[k]], iv)) continue;
          iv.entry_sphere = iv.entry >= near ? static_cast<int>(bins.items[k]) : -1;
          iv.exit_sphere = iv.exit <= far ? static_cast<int>(bins.items[k]) : -1;
          iv.entry = std::max(iv.entry, near);
          iv.exit = std::min(iv.exit, far);
          if (iv.entry < iv.exit) intervals.push_back(iv);
        }
        // Sec. 4.3: inner-full cells are fluid whose particles were left out.
        march_cells(cells, grid.view().eye, grid.view().world_ray(x, y), near, far,
                    [&](std::uint8_t state, double z_in, double z_out) {
                      if (cell::is_inner(state) && cell::occupancy(state) == cell::kFull)
                        intervals.push_back({z_in, z_out});
                    });
        builder.begin();
        auto& row = row_spans[static_cast<std::size_t>(y)];
        merge(intervals, scale, options.gap_bridging, [&](const Interval& iv) {
          const std::size_t stored = row.size();
          builder.add(iv.entry, iv.exit, scale);
          if (normals == nullptr) return;
          auto& row_n = row_normals[static_cast<std::size_t>(y)];
          const glm::vec3 exit_normal = sphere_normal(grid, spheres, iv.exit_sphere, d, iv.exit);
          if (row.size() > stored)
            row_n.push_back(
                {sphere_normal(grid, spheres, iv.entry_sphere, d, iv.entry), exit_normal});
          else row_n.back().exit = exit_normal;  // past the cap: the stored span was extended
        });
        image.pixels[static_cast<std::size_t>(x) + static_cast<std::size_t>(y) * width] =
            builder.end();
      }
    }
  });
  std::uint32_t offset = 0;
  for (int y = 0; y < height; ++y) {
    const auto& row = row_spans[static_cast<std::size_t>(y)];
    for (int x = 0; x < width; ++x)
      image.pixels[static_cast<std::size_t>(x) + static_cast<std::size_t>(y) * width].offset +=
          offset;
    image.spans.insert(image.spans.end(), row.begin(), row.end());
    if (normals != nullptr) {
      const auto& row_n = row_normals[static_cast<std::size_t>(y)];
      normals->insert(normals->end(), row_n.begin(), row_n.end());
    }
    offset += static_cast<std::uint32_t>(row.size());
  }
  return image;
}

}  // namespace voxspan
