#include "render/cpu/span_caster.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace voxspan {
namespace {

constexpr int kTile = SpanCaster::kTile;

struct Sphere {
  glm::dvec3 center;  // view space
  double radius;
};

struct Box {
  glm::dvec3 lo, hi;  // world space
};

struct Interval {
  double entry, exit;
};

// Items sorted into screen tiles by their pixel rectangles (counting sort: serial, linear).
struct TileBins {
  int nx = 0, ny = 0;
  std::vector<std::uint32_t> start;  // nx * ny + 1
  std::vector<std::uint32_t> items;

  void fill(int width, int height, const std::vector<PixelRect>& rects) {
    nx = (width + kTile - 1) / kTile;
    ny = (height + kTile - 1) / kTile;
    start.assign(std::size_t(nx) * std::size_t(ny) + 1, 0);
    for (const PixelRect& r : rects) each_tile(r, [&](std::size_t t) { ++start[t + 1]; });
    for (std::size_t t = 1; t < start.size(); ++t) start[t] += start[t - 1];
    items.resize(start.back());
    cursor.assign(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < rects.size(); ++i)
      each_tile(rects[i], [&](std::size_t t) { items[cursor[t]++] = std::uint32_t(i); });
  }
  std::span<const std::uint32_t> of(std::size_t tile) const {
    return {items.data() + start[tile], start[tile + 1] - start[tile]};
  }

 private:
  template <class F> void each_tile(const PixelRect& r, F&& f) const {
    for (int ty = r.y0 / kTile; ty <= r.y1 / kTile; ++ty)
      for (int tx = r.x0 / kTile; tx <= r.x1 / kTile; ++tx)
        f(std::size_t(tx) + std::size_t(ty) * std::size_t(nx));
  }
  std::vector<std::uint32_t> cursor;
};

// Depth interval of the ray z * d (view space) inside a sphere; false when it misses or only
// touches. The closest-approach form keeps precision for small, distant spheres.
bool chord(const glm::dvec3& d, double d2, const Sphere& s, Interval& out) {
  const double zc = glm::dot(d, s.center) / d2;
  const glm::dvec3 perp = s.center - zc * d;
  const double h2 = s.radius * s.radius - glm::dot(perp, perp);
  if (!(h2 > 0)) return false;
  const double half = std::sqrt(h2 / d2);
  out = {zc - half, zc + half};
  return true;
}

// Depth interval of the ray eye + z * w inside a box (slabs); false when it misses.
bool box_chord(const glm::dvec3& eye, const glm::dvec3& w, const Box& b, Interval& out) {
  double z0 = -1e300, z1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (w[a] == 0) {
      if (eye[a] < b.lo[a] || eye[a] >= b.hi[a]) return false;
      continue;
    }
    double ta = (b.lo[a] - eye[a]) / w[a], tb = (b.hi[a] - eye[a]) / w[a];
    if (ta > tb) std::swap(ta, tb);
    z0 = std::max(z0, ta);
    z1 = std::min(z1, tb);
  }
  out = {z0, z1};
  return z0 < z1;
}

// The runs of inner-full cells along x, as world boxes, with the pixels each may cover.
void cell_boxes(const PerspectiveGrid& grid, const CellStatesView& cells, std::vector<Box>& boxes,
                std::vector<PixelRect>& rects) {
  boxes.clear();
  rects.clear();
  if (cells.empty() || !(cells.cell_size > 0)) return;
  const double h = cells.cell_size;
  const glm::dvec3 origin(cells.origin[0], cells.origin[1], cells.origin[2]);
  const auto nx = std::size_t(cells.dims[0]), ny = std::size_t(cells.dims[1]);
  for (int k = 0; k < cells.dims[2]; ++k)
    for (int j = 0; j < cells.dims[1]; ++j) {
      const std::uint8_t* row = cells.states + nx * (std::size_t(j) + ny * std::size_t(k));
      for (int i = 0; i < cells.dims[0];) {
        if (row[i] != cell::kInnerFull) {
          ++i;
          continue;
        }
        int end = i + 1;
        while (end < cells.dims[0] && row[end] == cell::kInnerFull) ++end;
        // Faces as render/cell_march.h computes them, so that touching boxes meet exactly.
        const Box b{{origin.x + double(i) * h, origin.y + double(j) * h, origin.z + double(k) * h},
                    {origin.x + double(end) * h, origin.y + double(j + 1) * h,
                     origin.z + double(k + 1) * h}};
        const glm::dvec3 size = b.hi - b.lo;
        const PixelRect r =
            grid.sphere_pixels(grid.view().to_view(0.5 * (b.lo + b.hi)), 0.5 * glm::length(size));
        i = end;
        if (r.empty()) continue;
        boxes.push_back(b);
        rects.push_back(r);
      }
    }
}

PixelRect clip(const PixelRect& r, int x0, int y0, int x1, int y1) {
  return {std::max(r.x0, x0), std::max(r.y0, y0), std::min(r.x1, x1), std::min(r.y1, y1)};
}

// One tile's interval lists, per pixel of the tile; a thread's, reused from tile to tile.
struct TileLists {
  std::vector<std::vector<Interval>> at = std::vector<std::vector<Interval>>(kTile * kTile);
  std::vector<glm::dvec3> rays = std::vector<glm::dvec3>(kTile * kTile);
  std::int64_t chord_tests = 0;
};

}  // namespace

struct SpanCaster::Work {
  std::vector<Sphere> spheres;
  std::vector<PixelRect> sphere_rects, box_rects;
  std::vector<Box> boxes;
  TileBins sphere_bins, box_bins;
  std::vector<std::vector<Span>> tile_spans;
  std::vector<std::uint32_t> tile_base;  // the first span of each tile in the image
  tbb::enumerable_thread_specific<TileLists> lists;
};

SpanCaster::SpanCaster() : work_(std::make_unique<Work>()) {}
SpanCaster::~SpanCaster() = default;
SpanCaster::SpanCaster(SpanCaster&&) noexcept = default;
SpanCaster& SpanCaster::operator=(SpanCaster&&) noexcept = default;

CastCounts SpanCaster::run(const PerspectiveGrid& grid, std::span<const ParticleSphere> particles,
                           const CellStatesView& cells, const CastSettings& settings,
                           SpanImage& out) {
  Work& w = *work_;
  const int width = grid.width(), height = grid.height();
  out.grid = grid;
  out.pixels.assign(std::size_t(width) * std::size_t(height), PixelSpans{});
  out.spans.clear();
  CastCounts counts;
  if (grid.empty()) return counts;
  const ViewFrame& view = grid.view();
  const double near = grid.near(), far = grid.grid_far();

  w.spheres.clear();
  w.sphere_rects.clear();
  for (const ParticleSphere& p : particles) {
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
          std::isfinite(p.radius) && p.radius > 0))
      continue;
    const Sphere s{view.to_view(glm::dvec3(p.x, p.y, p.z)), p.radius};
    if (s.center.z + s.radius <= near) continue;
    const PixelRect r = grid.sphere_pixels(s.center, s.radius);
    if (r.empty()) continue;
    w.spheres.push_back(s);
    w.sphere_rects.push_back(r);
  }
  if (settings.use_cell_states) cell_boxes(grid, cells, w.boxes, w.box_rects);
  else w.boxes.clear(), w.box_rects.clear();
  w.sphere_bins.fill(width, height, w.sphere_rects);
  w.box_bins.fill(width, height, w.box_rects);
  const int tiles_x = w.sphere_bins.nx, tiles = tiles_x * w.sphere_bins.ny;
  w.tile_spans.resize(std::size_t(tiles));
  for (TileLists& l : w.lists) l.chord_tests = 0;

  tbb::parallel_for(tbb::blocked_range<int>(0, tiles), [&](const tbb::blocked_range<int>& range) {
    TileLists& l = w.lists.local();
    for (int t = range.begin(); t != range.end(); ++t) {
      const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
      const int x1 = std::min(x0 + kTile, width) - 1, y1 = std::min(y0 + kTile, height) - 1;
      const auto local = [&](int x, int y) { return std::size_t(x - x0 + (y - y0) * kTile); };
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          l.at[local(x, y)].clear();
          l.rays[local(x, y)] = view.view_ray(x, y);
        }
      const auto keep = [&](std::vector<Interval>& list, Interval iv) {
        iv.entry = std::max(iv.entry, near);
        iv.exit = std::min(iv.exit, far);
        if (iv.entry < iv.exit) list.push_back(iv);
      };
      for (std::uint32_t i : w.sphere_bins.of(std::size_t(t))) {
        const Sphere& s = w.spheres[i];
        const PixelRect r = clip(w.sphere_rects[i], x0, y0, x1, y1);
        l.chord_tests += r.area();
        for (int y = r.y0; y <= r.y1; ++y)
          for (int x = r.x0; x <= r.x1; ++x) {
            const glm::dvec3& d = l.rays[local(x, y)];
            Interval iv;
            if (chord(d, glm::dot(d, d), s, iv)) keep(l.at[local(x, y)], iv);
          }
      }
      // Sec. 4.3: inner-full cells are fluid whose particles were left out.
      for (std::uint32_t i : w.box_bins.of(std::size_t(t))) {
        const PixelRect r = clip(w.box_rects[i], x0, y0, x1, y1);
        for (int y = r.y0; y <= r.y1; ++y)
          for (int x = r.x0; x <= r.x1; ++x) {
            Interval iv;
            if (box_chord(view.eye, view.world_ray(x, y), w.boxes[i], iv))
              keep(l.at[local(x, y)], iv);
          }
      }
      std::vector<Span>& spans = w.tile_spans[std::size_t(t)];
      spans.clear();
      SpanListBuilder builder(spans, settings.max_spans);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          std::vector<Interval>& list = l.at[local(x, y)];
          std::sort(list.begin(), list.end(),
                    [](const Interval& a, const Interval& b) { return a.entry < b.entry; });
          const double scale = glm::length(l.rays[local(x, y)]);
          builder.begin();
          std::size_t k = 0;
          while (k < list.size()) {
            Interval cur = list[k++];
            while (k < list.size() && (list[k].entry <= cur.exit ||
                                       (list[k].entry - cur.exit) * scale < settings.gap_bridging))
              cur.exit = std::max(cur.exit, list[k++].exit);
            builder.add(cur.entry, cur.exit, scale);
          }
          out.pixels[std::size_t(x) + std::size_t(y) * std::size_t(width)] = builder.end();
        }
    }
  });

  // Tiles join in their order: offsets move by the spans of the tiles before.
  std::vector<std::uint32_t>& base = w.tile_base;
  base.assign(std::size_t(tiles) + 1, 0);
  for (int t = 0; t < tiles; ++t)
    base[std::size_t(t) + 1] =
        base[std::size_t(t)] + std::uint32_t(w.tile_spans[std::size_t(t)].size());
  out.spans.resize(base.back());
  tbb::parallel_for(tbb::blocked_range<int>(0, tiles), [&](const tbb::blocked_range<int>& range) {
    for (int t = range.begin(); t != range.end(); ++t) {
      const std::vector<Span>& spans = w.tile_spans[std::size_t(t)];
      std::copy(spans.begin(), spans.end(), out.spans.begin() + base[std::size_t(t)]);
      const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
      for (int y = y0; y < std::min(y0 + kTile, height); ++y)
        for (int x = x0; x < std::min(x0 + kTile, width); ++x)
          out.pixels[std::size_t(x) + std::size_t(y) * std::size_t(width)].offset +=
              base[std::size_t(t)];
    }
  });
  counts.spheres = std::int64_t(w.spheres.size());
  counts.cell_boxes = std::int64_t(w.boxes.size());
  counts.tiles = tiles;
  for (const TileLists& l : w.lists) counts.chord_tests += l.chord_tests;
  return counts;
}

}  // namespace voxspan
