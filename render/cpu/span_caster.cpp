#include "render/cpu/span_caster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "render/cpu/screen_bins.h"
#include "voxspan/stopwatch.h"

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

// A box of cells [lo, hi) in cell indices.
struct CellBox {
  glm::ivec3 lo, hi;
};

// The inner-full cells as few boxes (greedy: runs along x, runs of equal runs along y, then
// along z): the union is the same, and a ray through a calm body of water meets a few boxes
// instead of one cell after another.
// Scratch, kept from frame to frame: the merged boxes; the boxes still growing along z, the next
// ones, and one z-layer's rectangles (x runs grown along y).
struct BoxScratch {
  std::vector<CellBox> merged, open, next, slab;
};

void merge_inner_full(const CellStatesView& cells, std::vector<CellBox>& out, BoxScratch& w) {
  out.clear();
  std::vector<CellBox>&open = w.open, &next = w.next, &slab = w.slab;
  open.clear();
  const auto nx = std::size_t(cells.dims[0]), ny = std::size_t(cells.dims[1]);
  for (int k = 0; k <= cells.dims[2]; ++k) {
    slab.clear();
    if (k < cells.dims[2]) {
      std::size_t row_start = 0;  // first rectangle still growing along y
      for (int j = 0; j < cells.dims[1]; ++j) {
        const std::uint8_t* row = cells.states + nx * (std::size_t(j) + ny * std::size_t(k));
        const std::size_t before = slab.size();
        for (int i = 0; i < cells.dims[0];) {
          if (row[i] != cell::kInnerFull) {
            ++i;
            continue;
          }
          int end = i + 1;
          while (end < cells.dims[0] && row[end] == cell::kInnerFull) ++end;
          // Grow the rectangle of the row before with the same x run, else start one.
          bool grown = false;
          for (std::size_t r = row_start; r < before && !grown; ++r)
            if (slab[r].lo.x == i && slab[r].hi.x == end && slab[r].hi.y == j) {
              slab[r].hi.y = j + 1;
              grown = true;
            }
          if (!grown) slab.push_back({{i, j, k}, {end, j + 1, k + 1}});
          i = end;
        }
        // Rectangles that did not reach this row are finished along y.
        std::size_t keep = row_start;
        for (std::size_t r = row_start; r < slab.size(); ++r)
          if (slab[r].hi.y < j + 1) std::swap(slab[keep++], slab[r]);
        row_start = keep;
      }
    }
    // Grow the open boxes by this layer's equal rectangles; the rest of them close.
    next.clear();
    for (const CellBox& b : open) {
      bool grown = false;
      for (CellBox& r : slab)
        if (r.lo.x == b.lo.x && r.hi.x == b.hi.x && r.lo.y == b.lo.y && r.hi.y == b.hi.y &&
            r.lo.z == k && k < cells.dims[2]) {
          next.push_back({b.lo, {b.hi.x, b.hi.y, k + 1}});
          r.lo.z = -1;  // taken
          grown = true;
          break;
        }
      if (!grown) out.push_back(b);
    }
    for (const CellBox& r : slab)
      if (r.lo.z >= 0) next.push_back(r);
    std::swap(open, next);
  }
}

// The pixels whose centre rays may meet a world box: the bounds of its projected corners when
// all lie in front of the eye (the projection of a box is the hull of its corners'), else the
// bounds of its bounding sphere.
PixelRect box_pixels(const PerspectiveGrid& grid, const Box& b) {
  const ViewFrame& v = grid.view();
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p =
        v.to_view({c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z});
    if (!(p.z > 0))
      return grid.sphere_pixels(v.to_view(0.5 * (b.lo + b.hi)), 0.5 * glm::length(b.hi - b.lo));
    const double px = v.pixel_x(p.x / p.z), py = v.pixel_y(p.y / p.z);
    x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
  }
  // A margin of a pixel for rounding; clipped to the image.
  PixelRect r{int(std::ceil(std::max(x0 - 1, -1.0))), int(std::ceil(std::max(y0 - 1, -1.0))),
              int(std::floor(std::min(x1 + 1, double(v.width)))),
              int(std::floor(std::min(y1 + 1, double(v.height))))};
  r.x0 = std::max(r.x0, 0), r.y0 = std::max(r.y0, 0);
  r.x1 = std::min(r.x1, v.width - 1), r.y1 = std::min(r.y1, v.height - 1);
  return r;
}

// The inner-full cells as world boxes, with the pixels each may cover.
void cell_boxes(const PerspectiveGrid& grid, const CellStatesView& cells, BoxScratch& scratch,
                std::vector<Box>& boxes, std::vector<PixelRect>& rects) {
  boxes.clear();
  rects.clear();
  if (cells.empty() || !(cells.cell_size > 0)) return;
  std::vector<CellBox>& merged = scratch.merged;
  merge_inner_full(cells, merged, scratch);
  const double h = cells.cell_size;
  const glm::dvec3 origin(cells.origin[0], cells.origin[1], cells.origin[2]);
  for (const CellBox& c : merged) {
    // Faces as render/cell_march.h computes them, so that touching boxes meet exactly.
    const Box b{{origin.x + double(c.lo.x) * h, origin.y + double(c.lo.y) * h,
                 origin.z + double(c.lo.z) * h},
                {origin.x + double(c.hi.x) * h, origin.y + double(c.hi.y) * h,
                 origin.z + double(c.hi.z) * h}};
    const PixelRect r = box_pixels(grid, b);
    if (r.empty()) continue;
    boxes.push_back(b);
    rects.push_back(r);
  }
}

PixelRect clip(const PixelRect& r, const PixelRect& to) {
  return {std::max(r.x0, to.x0), std::max(r.y0, to.y0), std::min(r.x1, to.x1),
          std::min(r.y1, to.y1)};
}

// One tile's unions, per pixel of the tile; a thread's, reused from tile to tile. A pixel's
// union is its intervals `before` (in depth order) then `last`: the interval nearly every chord
// of a thick fluid lands in (spheres come nearest first), kept in a flat array so that the
// common case (moving its exit) touches no list. last[p].exit == kNone: the union is empty.
// A pixel's ray is (a[x], b[y], 1) in view space (ViewFrame::view_ray).
constexpr double kNone = -std::numeric_limits<double>::infinity();

struct TileLists {
  std::vector<std::vector<Interval>> before = std::vector<std::vector<Interval>>(kTile * kTile);
  Interval last[kTile * kTile];
  double a[kTile], b[kTile];
  double inv_d2[kTile * kTile];  // 1 / |ray|^2
  double scale[kTile * kTile];   // |ray|: a depth difference's length along the ray
  // One row of one sphere (row_chords).
  double zc[kTile], h2[kTile];
  double changes[kTile];  // > 0: the chord can change the union (a double: a bool mask
                          // keeps the compiler from vectorizing row_chords)
  std::int64_t chord_tests = 0, spans_found = 0, capped_pixels = 0;
};

// The chords of sphere s along row y of the tile, pixels [x0, x1] (tile-local): zc and h2 per
// pixel, as the reference's chord() computes them but for a multiplication by 1 / |ray|^2 where
// it divides (a rounding apart), and whether the chord can change the pixel's union: not when
// the ray misses the sphere (h2 <= 0) nor when the chord lies inside the union's last interval,
// tested without the square root (half <= m, m the chord centre's distance to that interval's
// nearer end). A quarter of the chords of thick fluid lie inside it. Branch-free, so that the
// compiler vectorizes it.
void row_chords(TileLists& l, const Sphere& s, int y, int x0, int x1) {
  const double b = l.b[y], r2 = s.radius * s.radius;
  const double cx = s.center.x, cy = s.center.y, cz = s.center.z;
  const double* inv_d2 = l.inv_d2 + y * kTile;
  const Interval* last = l.last + y * kTile;
  for (int x = x0; x <= x1; ++x) {
    const double a = l.a[x];
    const double zc = (a * cx + b * cy + cz) * inv_d2[x];
    const double px = cx - zc * a, py = cy - zc * b, pz = cz - zc;
    const double h2 = r2 - (px * px + py * py + pz * pz);
    const double m = std::min(last[x].exit - zc, zc - last[x].entry);
    // > 0 where half^2 > m^2 or m < 0: the chord reaches outside the last interval.
    const double outside = std::max(h2 * inv_d2[x] - m * m, -m);
    l.zc[x] = zc;
    l.h2[x] = h2;
    l.changes[x] = std::min(h2, outside);
  }
}

// Adds an interval to a pixel's union: `list` holds the union so far as disjoint intervals in
// depth order, gaps shorter than `gap` along the ray (depth difference times `scale`) closed.
// The same components, and the same comparisons, as sorting every interval by entry and
// merging in one sweep; but a ray through thick fluid meets dozens of spheres whose chords
// mostly overlap the last interval (the spheres come nearest first), so the list stays short
// and most additions only move its last exit.
void add_interval(std::vector<Interval>& list, Interval iv, double scale, double gap) {
  // Whether b, which starts no earlier than a, joins a's run.
  const auto joins = [&](const Interval& a, const Interval& b) {
    return b.entry <= a.exit || (b.entry - a.exit) * scale < gap;
  };
  if (list.empty() || list.back().entry <= iv.entry) {
    if (!list.empty() && joins(list.back(), iv))
      list.back().exit = std::max(list.back().exit, iv.exit);
    else list.push_back(iv);
    return;
  }
  // The first interval that starts after iv, and the one before it.
  std::size_t k =
      std::size_t(std::upper_bound(list.begin(), list.end(), iv.entry,
                                   [](double e, const Interval& c) { return e < c.entry; }) -
                  list.begin());
  std::size_t at = k;
  if (k > 0 && joins(list[k - 1], iv)) {
    at = k - 1;
    list[at].exit = std::max(list[at].exit, iv.exit);
  } else {
    list.insert(list.begin() + std::ptrdiff_t(k), iv);
  }
  // The run may now reach the intervals after it.
  std::size_t next = at + 1;
  while (next < list.size() && joins(list[at], list[next])) {
    list[at].exit = std::max(list[at].exit, list[next].exit);
    ++next;
  }
  list.erase(list.begin() + std::ptrdiff_t(at + 1), list.begin() + std::ptrdiff_t(next));
}

// Adds an interval to pixel p's union: add_interval on `before` then `last`, with its common
// case (the interval starts in or after `last`) on the flat array alone.
inline void join(TileLists& l, std::size_t p, Interval iv, double gap) {
  Interval& last = l.last[p];
  if (last.exit == kNone) {
    last = iv;
    return;
  }
  if (last.entry <= iv.entry) {
    if (iv.entry <= last.exit || (iv.entry - last.exit) * l.scale[p] < gap) {
      last.exit = std::max(last.exit, iv.exit);
    } else {
      l.before[p].push_back(last);
      last = iv;
    }
    return;
  }
  std::vector<Interval>& list = l.before[p];
  list.push_back(last);
  add_interval(list, iv, l.scale[p], gap);
  last = list.back();
  list.pop_back();
}

// What a chord keeps: its part in [near, far] (the grid's); in the union, gaps shorter than
// `gap` along the ray close.
struct DepthRule {
  double near, far, gap;
};

// A chord into pixel p's union (join), clipped by the rule.
inline void keep(TileLists& l, std::size_t p, Interval iv, const DepthRule& rule) {
  iv.entry = std::max(iv.entry, rule.near);
  iv.exit = std::min(iv.exit, rule.far);
  if (iv.entry < iv.exit) join(l, p, iv, rule.gap);
}

// ---- The phases of SpanCaster::run (span_caster.h's CastPhase), in the order they run: each
// reads the products of those before it and writes its own.

struct BinnedSphere {
  Sphere sphere;
  PixelRect rect;
};

// How many spheres are in view, and the depth range of their nearest points.
struct InView {
  std::size_t count = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
};

// project's product: the spheres and the inner-full cells' boxes with the pixels each may cover.
struct Projected {
  std::vector<Sphere> spheres;          // per particle, view space (stale where out of view)
  std::vector<PixelRect> sphere_rects;  // per particle; empty: out of view
  InView in_view;
  std::vector<Box> boxes;            // the inner-full cells merged, world space
  std::vector<PixelRect> box_rects;  // per box
};

// bin's product: per screen tile its spheres, nearest first, and its boxes.
struct TileBins {
  Bins sphere_bins, box_bins;         // per tile its range of `spheres`, of `boxes`
  std::vector<BinnedSphere> spheres;  // each tile's side by side: a tile reads them as a stream
  std::vector<std::uint32_t> boxes;   // indices into Projected::boxes

  std::span<const BinnedSphere> spheres_of(std::size_t t) const {
    return std::span(spheres).subspan(sphere_bins.start[t],
                                      sphere_bins.start[t + 1] - sphere_bins.start[t]);
  }
  std::span<const std::uint32_t> boxes_of(std::size_t t) const {
    return std::span(boxes).subspan(box_bins.start[t], box_bins.start[t + 1] - box_bins.start[t]);
  }
};

// What the tiles counted on the way (CastCounts).
struct TileTallies {
  std::int64_t chord_tests = 0, spans_found = 0, capped_pixels = 0;
};

// Project: every sphere to view space with the pixels it may cover (none: out of view), in
// parallel, and the depth range of the nearest points of those in view; the inner-full cells
// (none when `cells` is empty) as merged world boxes with theirs.
void project(const PerspectiveGrid& grid, std::span<const ParticleSphere> particles,
             const CellStatesView& cells, BoxScratch& scratch, Projected& out) {
  const ViewFrame& view = grid.view();
  const double near = grid.near();
  const std::size_t n = particles.size();
  out.spheres.resize(n);
  out.sphere_rects.resize(n);
  out.in_view = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 4096), InView{},
      [&](const tbb::blocked_range<std::size_t>& range, InView found) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const ParticleSphere& p = particles[i];
          out.sphere_rects[i] = {};
          if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
                std::isfinite(p.radius) && p.radius > 0))
            continue;
          const Sphere s{view.to_view(glm::dvec3(p.x, p.y, p.z)), p.radius};
          if (s.center.z + s.radius <= near) continue;
          const PixelRect r = grid.sphere_pixels(s.center, s.radius);
          if (r.empty()) continue;
          out.spheres[i] = s;
          out.sphere_rects[i] = r;
          ++found.count;
          found.lo = std::min(found.lo, s.center.z - s.radius);
          found.hi = std::max(found.hi, s.center.z - s.radius);
        }
        return found;
      },
      [](InView a, const InView& b) {
        return InView{a.count + b.count, std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
      });
  cell_boxes(grid, cells, scratch, out.boxes, out.box_rects);
}

// Sort: the spheres in view, nearest first, to a kDepthBins-th of the depth range (a counting
// sort: two passes instead of n log n comparisons). The tiles keep this order, so each pixel's
// chords arrive almost in depth order and most of them only move the last exit of its union
// (join). The union does not depend on the order. At 100 k particles 8 439 of 1.17 M joins take
// the slow path with 256 bins, 7 798 with 4 096, 165 742 with 16.
void sort_by_depth(const Projected& in, Bins& depth_bins, std::vector<BinnedSphere>& sorted) {
  constexpr std::size_t kDepthBins = 256;
  const InView& in_view = in.in_view;
  const double per_depth =
      in_view.hi > in_view.lo ? double(kDepthBins - 1) / (in_view.hi - in_view.lo) : 0.0;
  const auto depth_bin = [&](std::size_t i, auto&& f) {
    if (in.sphere_rects[i].empty()) return;
    const Sphere& s = in.spheres[i];
    f(std::size_t((s.center.z - s.radius - in_view.lo) * per_depth));
  };
  depth_bins.count(kDepthBins, in.spheres.size(), depth_bin);
  sorted.resize(in_view.count);
  depth_bins.place(depth_bin, [&](std::size_t i, std::size_t slot) {
    sorted[slot] = {in.spheres[i], in.sphere_rects[i]};
  });
}

// Bin: the boxes and the sorted spheres into the tiles their pixels touch, each tile's in the
// order they come.
void bin_to_tiles(const Tiles& screen, std::span<const BinnedSphere> sorted,
                  std::span<const PixelRect> box_rects, TileBins& out) {
  const auto box_tiles = [&](std::size_t i, auto&& f) { screen.each(box_rects[i], f); };
  out.box_bins.count(screen.count(), box_rects.size(), box_tiles);
  out.boxes.resize(out.box_bins.size());
  out.box_bins.place(box_tiles,
                     [&](std::size_t i, std::size_t slot) { out.boxes[slot] = std::uint32_t(i); });
  const auto sphere_tiles = [&](std::size_t k, auto&& f) { screen.each(sorted[k].rect, f); };
  out.sphere_bins.count(screen.count(), sorted.size(), sphere_tiles);
  out.spheres.resize(out.sphere_bins.size());
  out.sphere_bins.place(sphere_tiles,
                        [&](std::size_t k, std::size_t slot) { out.spheres[slot] = sorted[k]; });
}

// Pixel (x, y)'s place in a tile's arrays.
inline std::size_t local(const PixelRect& tile, int x, int y) {
  return std::size_t(x - tile.x0 + (y - tile.y0) * kTile);
}

// The rays of a tile's pixels and their empty unions: per column a, per row b (view space),
// per pixel 1 / |ray|^2 and |ray|.
void start_tile(TileLists& l, const PixelRect& tile, const ViewFrame& view) {
  for (int x = tile.x0; x <= tile.x1; ++x) l.a[x - tile.x0] = view.view_ray(x, tile.y0).x;
  for (int y = tile.y0; y <= tile.y1; ++y) l.b[y - tile.y0] = view.view_ray(tile.x0, y).y;
  for (int y = tile.y0; y <= tile.y1; ++y)
    for (int x = tile.x0; x <= tile.x1; ++x) {
      const std::size_t p = local(tile, x, y);
      l.before[p].clear();
      l.last[p] = {kNone, kNone};
      const double a = l.a[x - tile.x0], b = l.b[y - tile.y0];
      const double d2 = a * a + b * b + 1.0;
      l.inv_d2[p] = 1 / d2;
      l.scale[p] = std::sqrt(d2);
    }
}

// The spheres' chords over the tile, into its pixels' unions: row_chords per row of each sphere,
// the square root only where the chord can change the union.
void sphere_chords(TileLists& l, const PixelRect& tile, std::span<const BinnedSphere> spheres,
                   const DepthRule& rule) {
  for (const BinnedSphere& binned : spheres) {
    const PixelRect r = clip(binned.rect, tile);
    l.chord_tests += r.area();
    for (int y = r.y0 - tile.y0; y <= r.y1 - tile.y0; ++y) {
      row_chords(l, binned.sphere, y, r.x0 - tile.x0, r.x1 - tile.x0);
      for (int x = r.x0 - tile.x0; x <= r.x1 - tile.x0; ++x) {
        if (!(l.changes[x] > 0)) continue;
        const double half = std::sqrt(l.h2[x] * l.inv_d2[x + y * kTile]);
        keep(l, std::size_t(x + y * kTile), {l.zc[x] - half, l.zc[x] + half}, rule);
      }
    }
  }
}

// Sec. 4.3: inner-full cells are fluid whose particles were left out. The chords of the tile's
// boxes (`items` into `in`'s) into its pixels' unions.
void box_chords(TileLists& l, const PixelRect& tile, const ViewFrame& view,
                std::span<const std::uint32_t> items, const Projected& in, const DepthRule& rule) {
  for (const std::uint32_t i : items) {
    const PixelRect r = clip(in.box_rects[i], tile);
    for (int y = r.y0; y <= r.y1; ++y)
      for (int x = r.x0; x <= r.x1; ++x) {
        Interval iv;
        if (box_chord(view.eye, view.world_ray(x, y), in.boxes[i], iv))
          keep(l, local(tile, x, y), iv, rule);
      }
  }
}

// The tile's unions as its spans (SpanListBuilder: the span cap), each pixel's PixelSpans into
// `pixels` (rows of `width`) with its offset into the tile's spans.
void tile_spans(TileLists& l, const PixelRect& tile, std::uint32_t max_spans,
                std::vector<Span>& spans, std::span<PixelSpans> pixels, int width) {
  spans.clear();
  SpanListBuilder builder(spans, max_spans);
  for (int y = tile.y0; y <= tile.y1; ++y)
    for (int x = tile.x0; x <= tile.x1; ++x) {
      const std::size_t p = local(tile, x, y);
      const double scale = l.scale[p];
      builder.begin();
      for (const Interval& iv : l.before[p]) builder.add(iv.entry, iv.exit, scale);
      if (l.last[p].exit != kNone) builder.add(l.last[p].entry, l.last[p].exit, scale);
      const PixelSpans found = builder.end();
      l.spans_found += found.total;
      l.capped_pixels += found.capped();
      pixels[std::size_t(x) + std::size_t(y) * std::size_t(width)] = found;
    }
}

// Per pixel slot of a tile, the largest capacity any thread's list has had. Which thread
// casts which tile changes from frame to frame, so a thread's lists grew whenever it first met
// a busier tile, long after the sizes were stable (the one-off allocations StepAllocations saw
// on the solver's thread): each thread grows its own lists to these before casting, where a
// reservation is its own.
using SlotCapacities = std::array<std::size_t, std::size_t(kTile* kTile)>;

SlotCapacities largest_capacities(const tbb::enumerable_thread_specific<TileLists>& lists) {
  SlotCapacities most{};
  for (const TileLists& l : lists)
    for (std::size_t p = 0; p < most.size(); ++p)
      most[p] = std::max(most[p], l.before[p].capacity());
  return most;
}

void grow_to(TileLists& l, const SlotCapacities& most) {
  for (std::size_t p = 0; p < most.size(); ++p)
    if (l.before[p].capacity() < most[p]) l.before[p].reserve(most[p]);
}

// Cast tiles: per tile, in parallel, each pixel's union of the chords of the tile's spheres and
// boxes, and from the unions the tile's spans; every pixel of `pixels` written, its offset into
// its tile's spans. Memory: one union per pixel of the tiles in flight.
TileTallies cast_tiles(const PerspectiveGrid& grid, const CastSettings& settings,
                       const Tiles& screen, const TileBins& bins, const Projected& in,
                       tbb::enumerable_thread_specific<TileLists>& lists,
                       std::vector<std::vector<Span>>& tile_spans_out,
                       std::vector<PixelSpans>& pixels) {
  pixels.assign(std::size_t(screen.width) * std::size_t(screen.height), PixelSpans{});
  tile_spans_out.resize(screen.count());
  const SlotCapacities most = largest_capacities(lists);
  for (TileLists& l : lists) l.chord_tests = l.spans_found = l.capped_pixels = 0;
  const ViewFrame& view = grid.view();
  const DepthRule rule{grid.near(), grid.grid_far(), settings.gap_bridging};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, screen.count()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      TileLists& l = lists.local();
                      grow_to(l, most);
                      for (std::size_t t = range.begin(); t != range.end(); ++t) {
                        const PixelRect tile = screen.rect(t);
                        start_tile(l, tile, view);
                        sphere_chords(l, tile, bins.spheres_of(t), rule);
                        box_chords(l, tile, view, bins.boxes_of(t), in, rule);
                        tile_spans(l, tile, settings.max_spans, tile_spans_out[t], pixels,
                                   screen.width);
                      }
                    });
  TileTallies sum;
  for (const TileLists& l : lists) {
    sum.chord_tests += l.chord_tests;
    sum.spans_found += l.spans_found;
    sum.capped_pixels += l.capped_pixels;
  }
  return sum;
}

// Join: the tiles' spans into `out` in tile order, each pixel's offset moved by the spans of the
// tiles before its own, so that the image does not depend on the threads. `base`: scratch.
void join_tiles(const Tiles& screen, const std::vector<std::vector<Span>>& tile_spans,
                std::vector<std::uint32_t>& base, SpanImage& out) {
  const std::size_t tiles = screen.count();
  base.assign(tiles + 1, 0);
  for (std::size_t t = 0; t < tiles; ++t)
    base[t + 1] = base[t] + std::uint32_t(tile_spans[t].size());
  out.spans.resize(base.back());
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, tiles), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t t = range.begin(); t != range.end(); ++t) {
          std::copy(tile_spans[t].begin(), tile_spans[t].end(), out.spans.begin() + base[t]);
          const PixelRect r = screen.rect(t);
          for (int y = r.y0; y <= r.y1; ++y)
            for (int x = r.x0; x <= r.x1; ++x)
              out.pixels[std::size_t(x) + std::size_t(y) * std::size_t(screen.width)].offset +=
                  base[t];
        }
      });
}

}  // namespace

// Each phase's product, kept from frame to frame (their storage reused).
struct SpanCaster::Work {
  Projected projected;
  BoxScratch box_scratch;
  Bins depth_bins;
  std::vector<BinnedSphere> sorted;  // the spheres in view, nearest first
  TileBins tile_bins;
  tbb::enumerable_thread_specific<TileLists> lists;
  std::vector<std::vector<Span>> tile_spans;  // per tile
  std::vector<std::uint32_t> tile_base;       // the first span of each tile in the image
};

SpanCaster::SpanCaster() : work_(std::make_unique<Work>()) {}
SpanCaster::~SpanCaster() = default;
SpanCaster::SpanCaster(SpanCaster&&) noexcept = default;
SpanCaster& SpanCaster::operator=(SpanCaster&&) noexcept = default;

CastCounts SpanCaster::run(const PerspectiveGrid& grid, std::span<const ParticleSphere> particles,
                           const CellStatesView& cells, const CastSettings& settings,
                           SpanImage& out) {
  Work& w = *work_;
  out.grid = grid;
  out.spans.clear();
  CastCounts counts;
  if (grid.empty()) {
    out.pixels.assign(std::size_t(grid.width()) * std::size_t(grid.height()), PixelSpans{});
    return counts;
  }
  // Each phase's wall time, read between the phases (nothing inside them).
  Stopwatch clock;
  const auto lap = [&](CastPhase p) {
    counts.phase_ms[std::size_t(p)] = clock.ms();
    clock.restart();
  };
  const Tiles screen(grid.width(), grid.height(), kTile);
  project(grid, particles, settings.use_cell_states ? cells : CellStatesView{}, w.box_scratch,
          w.projected);
  lap(CastPhase::project);
  sort_by_depth(w.projected, w.depth_bins, w.sorted);
  lap(CastPhase::sort);
  bin_to_tiles(screen, w.sorted, w.projected.box_rects, w.tile_bins);
  lap(CastPhase::bin);
  const TileTallies tallies = cast_tiles(grid, settings, screen, w.tile_bins, w.projected, w.lists,
                                         w.tile_spans, out.pixels);
  lap(CastPhase::cast_tiles);
  join_tiles(screen, w.tile_spans, w.tile_base, out);
  lap(CastPhase::join);

  counts.spheres = std::int64_t(w.projected.in_view.count);
  counts.cell_boxes = std::int64_t(w.projected.boxes.size());
  counts.tiles = std::int64_t(screen.count());
  counts.chord_tests = tallies.chord_tests;
  counts.spans_found = tallies.spans_found;
  counts.capped_pixels = tallies.capped_pixels;
  return counts;
}

}  // namespace voxspan
