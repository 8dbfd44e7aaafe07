#include "render/cpu/volume_caster.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "render/cpu/screen_bins.h"
#include "render/cpu/volume_adaptive.h"
#include "render/cpu/volume_lod.h"
#include "render/cpu/volume_march.h"
#include "render/cpu/volume_supports.h"
#include "render/model/volume_host.h"
#include "render/perspective_grid.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace voxspan {

using volume_cast::add_field_sums;
using volume_cast::bin_supports;
using volume_cast::kTile;
using volume_cast::project;
using volume_cast::Samples;
using volume_cast::sort_supports;
using volume_cast::Support;
using volume_cast::TileCells;
using volume_cast::TileMarch;
using volume_cast::TilePart;
using volume_cast::TileScratch;

namespace {

// The most samples one support may span: its rays' pending samples live in a window this long
// per pixel of a tile in flight (16 bytes each). A support larger than that (a particle around
// the eye at a fine lattice) is refused with the reason.
constexpr std::int64_t kMaxSupportSamples = std::int64_t(1) << 16;

}  // namespace

struct VolumeCaster::Work {
  std::vector<Support> projected;   // per particle, in input order
  std::vector<std::uint64_t> keys;  // (first - base) << 32 | position in `projected`
  std::vector<Support> supports;    // those in view, nearest first
  Bins tile_bins;
  std::vector<std::uint32_t> tile_lists;  // per tile its supports, in order
  Samples samples;
  tbb::enumerable_thread_specific<TileScratch> scratch;
  std::optional<TransferBounds> transfer_bounds;  // adaptive sampling's, of the frame
  bool cull_tiles = true;                         // set_tile_culling
  // The frame the last start_frame() began, for run_part() and field_sums().
  Camera camera;
  VolumeOptions options;
  ViewFrame frame;
  std::vector<TilePart> tile_parts;
  std::vector<TileCells> tile_cells;  // setup()'s plans, per tile
  VolumeLod lod;                      // level of detail: the particles drawn of those given
};

VolumeCaster::VolumeCaster() : work_(std::make_unique<Work>()) {}
VolumeCaster::~VolumeCaster() = default;
void VolumeCaster::set_tile_culling(bool on) { work_->cull_tiles = on; }

template <class Lap>
VolumeCounts VolumeCaster::start_frame(const Camera& camera,
                                       std::span<const VolumeParticle> particles,
                                       const VolumeOptions& options, Lap&& lap) {
  validate(camera);
  validate(options);
  if (const Backdrop* b = options.backdrop;
      b != nullptr && (b->width != camera.width || b->height != camera.height))
    throw make_error("the walls' backdrop is ", b->width, "x", b->height, ", the view ",
                     camera.width, "x", camera.height);
  Work& w = *work_;
  w.camera = camera;
  w.options = options;
  VolumeCounts counts;
  counts.particles = std::int64_t(particles.size());
  const double support = kernel_support(options.kernel);
  // The supports' pixel rectangles: PerspectiveGrid::sphere_pixels over any depth range.
  const PerspectiveGrid view_grid = PerspectiveGrid::over(camera, 1, 2, GridOptions{});
  w.frame = view_grid.view();
  if (options.level_of_detail > 0) {
    LodCounts lod;
    particles = w.lod.run(w.frame, particles, options.level_of_detail, lod);
    counts.particles_merged = lod.merged;
    counts.particles_coarse = lod.coarse;
  }
  Samples& s = w.samples;
  s.lattice = volume_lattice(w.frame.tan_half_y, w.frame.height, options);
  s.near =
      options.anchor;  // one spacing in front of the eye: a camera inside the fluid sees from there
  project(view_grid, s, particles, support, counts, w.projected);
  lap(VolumeCastPhase::project);

  std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = lo;
  hi = std::numeric_limits<std::int64_t>::min();
  for (const Support& p : w.projected)
    if (!p.rect.empty()) lo = std::min(lo, p.first), hi = std::max(hi, p.last);
  if (hi < lo) lo = hi = 0;
  for (const Support& p : w.projected)
    if (!p.rect.empty() && p.last - p.first + 1 > kMaxSupportSamples)
      throw make_error("a particle's support spans ", p.last - p.first + 1,
                       " samples along the view (at most ", kMaxSupportSamples,
                       "): a smoothing length far above the particle spacing, or a particle "
                       "around the eye; coarsen `sampling` or move the camera");
  s.base = lo;
  s.depths.resize(std::size_t(hi - lo + 2));
  for (std::size_t k = 0; k < s.depths.size(); ++k)
    s.depths[k] = s.lattice.depth(lo + std::int64_t(k));
  sort_supports(w.projected, s.base, w.keys, w.supports);
  lap(VolumeCastPhase::sort);

  bin_supports(Tiles(camera.width, camera.height, kTile), w.supports, w.tile_bins, w.tile_lists);
  lap(VolumeCastPhase::bin);
  return counts;
}

namespace {

// Adaptive sampling's transfer bounds for a frame of `options`, made in `bounds`, or null where
// adaptive sampling does not apply: its bounds hold for DVR of a Shepard-normalised field (a
// convex combination of the particles' values); otherwise every sample, as at tolerance 0.
const TransferBounds* adaptive_bounds(const VolumeOptions& options,
                                      std::optional<TransferBounds>& bounds) {
  if (!(options.adaptive.error_tolerance > 0 && options.mode == VolumeMode::dvr && options.shepard))
    return nullptr;
  return &bounds.emplace(options);
}

// f(march, tile rect, tile index, its supports) for every tile of the frame, in parallel, with
// the march of kernel K (of a rank's part with kPart) on this thread.
template <bool kPart, class F>
void each_tile(const Samples& s, const VolumeOptions& options, const ViewFrame& frame,
               const Bins& bins, const std::vector<std::uint32_t>& lists,
               tbb::enumerable_thread_specific<TileScratch>& scratch, VolumeCounts& counts,
               const PixelRanges* shared, const TransferBounds* tf, bool cull, F&& f) {
  const Tiles screen(frame.width, frame.height, kTile);
  tbb::enumerable_thread_specific<model::VolumeHost> hosts(options);
  tbb::combinable<VolumeCounts> tallies;
  with_kernel(options.kernel, [&]<SphKernel K>() {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, screen.count(), 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        TileMarch<K, kPart> march(s, options, frame, hosts.local(), scratch.local(),
                                                  tallies.local(), shared, tf, cull);
                        for (std::size_t t = range.begin(); t != range.end(); ++t) {
                          const std::span<const std::uint32_t> list(
                              lists.data() + bins.start[t], lists.data() + bins.start[t + 1]);
                          f(march, screen.rect(t), t, list);
                        }
                      });
  });
  tallies.combine_each([&](const VolumeCounts& t) { counts += t; });
}

}  // namespace

VolumeCounts VolumeCaster::run(const Camera& camera, std::span<const VolumeParticle> particles,
                               const VolumeOptions& options, VolumeFrame& out,
                               std::array<double, kVolumeCastPhaseNames.size()>* phase_ms) {
  Stopwatch clock;
  const auto lap = [&](VolumeCastPhase p) {
    if (phase_ms != nullptr) (*phase_ms)[std::size_t(p)] = clock.ms();
    clock.restart();
  };
  VolumeCounts counts = start_frame(camera, particles, options, lap);
  Work& w = *work_;
  out.reset(camera.width, camera.height);
  each_tile<false>(w.samples, w.options, w.frame, w.tile_bins, w.tile_lists, w.scratch, counts,
                   nullptr, adaptive_bounds(w.options, w.transfer_bounds), w.cull_tiles,
                   [&](auto& march, const PixelRect& rect, std::size_t, auto list) {
                     march.run(rect, list, w.supports, out);
                   });
  lap(VolumeCastPhase::march);
  return counts;
}

VolumeCounts VolumeCaster::cover(const Camera& camera, std::span<const VolumeParticle> particles,
                                 const VolumeOptions& options, std::vector<SampleRange>& hulls) {
  VolumeCounts counts = start_frame(camera, particles, options, [](VolumeCastPhase) {});
  Work& w = *work_;
  const std::int64_t n = std::int64_t(w.samples.base) + std::int64_t(w.samples.depths.size());
  if (w.samples.base < std::numeric_limits<std::int32_t>::min() / 2 ||
      n > std::numeric_limits<std::int32_t>::max() / 2)
    throw make_error("the view's samples run from index ", w.samples.base, " to ", n,
                     ": too far from the particle spacing's depth to merge across ranks");
  hulls.assign(std::size_t(camera.width) * std::size_t(camera.height), SampleRange{});
  VolumeCounts unused;
  each_tile<false>(w.samples, w.options, w.frame, w.tile_bins, w.tile_lists, w.scratch, unused,
                   nullptr, nullptr, w.cull_tiles,
                   [&](auto& march, const PixelRect& rect, std::size_t, auto list) {
                     march.cover(rect, list, w.supports, hulls);
                   });
  return counts;
}

VolumeCounts VolumeCaster::run_part(const PixelRanges& shared, VolumePart& out) {
  Work& w = *work_;
  const Tiles screen(w.frame.width, w.frame.height, kTile);
  w.tile_parts.resize(screen.count());
  VolumeCounts counts;
  each_tile<true>(w.samples, w.options, w.frame, w.tile_bins, w.tile_lists, w.scratch, counts,
                  &shared, adaptive_bounds(w.options, w.transfer_bounds), w.cull_tiles,
                  [&](auto& march, const PixelRect& rect, std::size_t t, auto list) {
                    march.run_part(rect, list, w.supports, w.tile_parts[t]);
                  });
  // The tiles' items into per-pixel order.
  const std::size_t pixels = std::size_t(w.frame.width) * std::size_t(w.frame.height);
  out.width = w.frame.width;
  out.height = w.frame.height;
  out.raw_start.assign(pixels + 1, 0);
  out.segment_start.assign(pixels + 1, 0);
  const auto each_pixel = [&](auto&& f) {
    for (std::size_t t = 0; t < screen.count(); ++t) {
      const PixelRect r = screen.rect(t);
      const TilePart& part = w.tile_parts[t];
      std::size_t raw = 0, segment = 0;
      for (int y = r.y0; y <= r.y1; ++y)
        for (int x = r.x0; x <= r.x1; ++x) {
          const std::size_t p =
              std::size_t(x - r.x0) + std::size_t(y - r.y0) * std::size_t(r.x1 - r.x0 + 1);
          const std::size_t pixel = std::size_t(x) + std::size_t(y) * std::size_t(out.width);
          f(part, pixel, raw, part.raw_count[p], segment, part.segment_count[p]);
          raw += part.raw_count[p];
          segment += part.segment_count[p];
        }
    }
  };
  each_pixel([&](const TilePart&, std::size_t pixel, std::size_t, std::uint32_t raws, std::size_t,
                 std::uint32_t segments) {
    out.raw_start[pixel + 1] = raws;
    out.segment_start[pixel + 1] = segments;
  });
  for (std::size_t p = 0; p < pixels; ++p) {
    out.raw_start[p + 1] += out.raw_start[p];
    out.segment_start[p + 1] += out.segment_start[p];
  }
  out.raws.resize(out.raw_start[pixels]);
  out.segments.resize(out.segment_start[pixels]);
  each_pixel([&](const TilePart& part, std::size_t pixel, std::size_t raw, std::uint32_t raws,
                 std::size_t segment, std::uint32_t segments) {
    std::copy_n(part.raws.begin() + std::ptrdiff_t(raw), raws,
                out.raws.begin() + std::ptrdiff_t(out.raw_start[pixel]));
    std::copy_n(part.segments.begin() + std::ptrdiff_t(segment), segments,
                out.segments.begin() + std::ptrdiff_t(out.segment_start[pixel]));
  });
  return counts;
}

void VolumeCaster::field_sums(std::span<const HitQuery> queries,
                              std::vector<FieldSums>& out) const {
  const Work& w = *work_;
  const Tiles screen(w.frame.width, w.frame.height, kTile);
  const std::size_t first = out.size();
  out.resize(first + queries.size());
  with_kernel(w.options.kernel, [&]<SphKernel K>() {
    tbb::parallel_for(std::size_t(0), queries.size(), [&](std::size_t q) {
      const int x = int(queries[q].pixel % std::uint32_t(w.frame.width));
      const int y = int(queries[q].pixel / std::uint32_t(w.frame.width));
      const std::size_t t = screen.of(x, y);
      const glm::dvec3 point = double(queries[q].depth) * w.frame.view_ray(x, y);
      FieldSums& sums = out[first + q];
      for (std::uint32_t k = w.tile_bins.start[t]; k < w.tile_bins.start[t + 1]; ++k) {
        const Support& s = w.supports[w.tile_lists[k]];
        if (x >= s.rect.x0 && x <= s.rect.x1 && y >= s.rect.y0 && y <= s.rect.y1)
          add_field_sums<K>(point, s, sums);
      }
    });
  });
}

namespace {

// The tiles' plans into one GpuPlans for a frame of `bundles` bundles.
void pack_plans(const std::vector<TileCells>& tiles, std::size_t bundles, GpuPlans& out) {
  static_assert(kSuperPixel < (1u << GpuPlans::kLevelBits));
  constexpr std::uint32_t kLevelMask = (1u << GpuPlans::kLevelBits) - 1;
  out.bundle_cells.assign(bundles, GpuPlans::kFullRate);
  out.cells.clear();
  out.super_pixels.clear();
  for (const TileCells& t : tiles) {
    const std::uint32_t supers = std::uint32_t(out.super_pixels.size()) << GpuPlans::kLevelBits;
    for (std::size_t k = 0; k < t.bundles.size(); ++k) {
      out.bundle_cells[t.bundles[k]] = std::uint32_t(out.cells.size());
      for (std::size_t c = k * t.per_bundle; c < (k + 1) * t.per_bundle; ++c) {
        const std::uint32_t word = t.cells[c];
        out.cells.push_back((word & kLevelMask) == kSuperPixel ? word + supers : word);
      }
    }
    out.super_pixels.insert(out.super_pixels.end(), t.super_pixels.begin(), t.super_pixels.end());
  }
}

}  // namespace

VolumeCounts VolumeCaster::setup(const Camera& camera, std::span<const VolumeParticle> particles,
                                 const VolumeOptions& options, VolumeSetup& out) {
  VolumeCounts counts = start_frame(camera, particles, options, [](VolumeCastPhase) {});
  Work& w = *work_;
  // The supports in view in their sorted order, and the tiles' lists of their positions.
  out.supports.resize(w.supports.size());
  for (std::size_t k = 0; k < w.supports.size(); ++k) {
    const Support& s = w.supports[k];
    out.supports[k] = {s.c.x,
                       s.c.y,
                       s.c.z,
                       s.radius,
                       float(s.inv_h),
                       float(s.v),
                       float(s.vq),
                       0.0f,
                       std::int32_t(s.first - w.samples.base),
                       std::int32_t(s.last - w.samples.base),
                       s.rect.x0,
                       s.rect.y0,
                       s.rect.x1,
                       s.rect.y1,
                       0,
                       0};
  }
  out.tile_start = w.tile_bins.start;
  out.tile_lists = w.tile_lists;
  out.tiles_x = Tiles(camera.width, camera.height, kTile).nx;
  out.base = w.samples.base;
  out.depths = w.samples.depths;
  out.near = w.samples.near;
  out.lattice = w.samples.lattice;
  const TransferBounds* tf = adaptive_bounds(w.options, w.transfer_bounds);
  out.adaptive = tf != nullptr;
  out.plans.bundle_cells.clear();
  out.plans.cells.clear();
  out.plans.super_pixels.clear();
  if (out.adaptive) {
    const Tiles screen(camera.width, camera.height, kTile);
    w.tile_cells.resize(screen.count());
    each_tile<false>(w.samples, w.options, w.frame, w.tile_bins, w.tile_lists, w.scratch, counts,
                     nullptr, tf, w.cull_tiles,
                     [&](auto& march, const PixelRect& rect, std::size_t t, auto list) {
                       march.plan_for_float_sums(rect, list, w.supports, w.tile_cells[t]);
                     });
    const std::size_t bundles = std::size_t((camera.width + kBundle - 1) / kBundle) *
                                std::size_t((camera.height + kBundle - 1) / kBundle);
    pack_plans(w.tile_cells, bundles, out.plans);
  }
  return counts;
}

}  // namespace voxspan
