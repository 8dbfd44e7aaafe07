#include "render/cpu/volume_caster.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "render/cpu/screen_bins.h"
#include "render/cpu/volume_adaptive.h"
#include "render/cpu/volume_lod.h"
#include "render/model/volume_host.h"
#include "render/perspective_grid.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace voxspan {
namespace {

constexpr int kTile = VolumeCaster::kTile;
constexpr int kTilePixels = kTile * kTile;
// The most samples one support may span: its rays' pending samples live in a window this long
// per pixel of a tile in flight (16 bytes each). A support larger than that (a particle around
// the eye at a fine lattice) is refused with the reason.
constexpr std::int64_t kMaxSupportSamples = std::int64_t(1) << 16;
// Occlusion culling: how far (samples of depth) a tile's supports advance between two looks at
// whether all its rays are opaque. Each look walks the tile's rays once; a support walks its
// chords' samples.
constexpr std::int64_t kSweepSamples = 8;

// TileScratch::bundle's mark of a pixel whose bundle is at full rate in every cell.
constexpr std::uint8_t kFullRate = 0xff;
static_assert((kTile / kBundle) * (kTile / kBundle) < kFullRate, "a tile's bundles in a byte");
// Plans for a march summing in float (VolumeCaster::setup): a sample is proven defined where the
// weight's lower bound is at least the floor times 1 + this, for the float sum of a few hundred
// positive terms (a relative error of at most n 2^-24) to stay at or above the floor.
constexpr double kFloatSumsMargin = 1e-4;

// A particle's support in view space, as the march reads it.
struct Support {
  glm::dvec3 c;            // centre
  double radius = 0;       // R = kernel support * h
  double inv_h = 0;        // 1 / h
  double vq = 0, v = 0;    // weight q and weight: the kernel's shape times these is the sum
  std::int64_t first = 0;  // the first sample at or after its nearest depth (and the near clip)
  std::int64_t last = -1;  // the last sample at or before its farthest depth
  double first_depth = 0;  // that first sample's depth
  double per_depth = 0;    // 1 / (k first_depth): samples per unit of depth there
  PixelRect rect;
};

// The frame's samples: depth(i) for i in [base, base + depth.size()).
struct Samples {
  VolumeLattice lattice;
  double near = 0;  // the near clip: no sample before it
  std::int64_t base = 0;
  std::vector<double> depths;
  double depth(std::int64_t i) const { return depths[std::size_t(i - base)]; }
};

// A ray's state in the march.
struct RayState {
  model::VolumeHost::VolumeRay ray;
  std::int64_t front = 0;  // the next sample to composite
  // The first sample behind the pixel's walls (VolumeOptions::backdrop): the ray ends there.
  std::int64_t wall = std::numeric_limits<std::int64_t>::max();
  std::int64_t last = -1;     // the last sample some support added to
  float scale = 1;            // world length per unit of depth
  float first_depth = 0;      // VolumeFrame::depth
  bool first_is_hit = false;  // first_depth is the first iso hit's
  bool done = false;
  std::int64_t super_cell = std::numeric_limits<std::int64_t>::min();  // its last super-pixel's
  model::RayHits hits;
  // A rank's part (run_part): the next of the pixel's shared ranges, and the segment being
  // composited (its index among the pixel's; -1: none), with the ray's unlit light and hit
  // count when it opened.
  std::uint32_t next_shared = 0;
  int open = -1;
  model::vec3 unlit_at_open{0.0f};
};

// A segment as the march builds it: which of the ray's hits it holds.
struct LocalSegment {
  PartSegment out;
  int hit_begin = 0, hit_end = 0;
};

// One tile's part: per pixel of the tile (row-major in the tile) its counts, then the items.
struct TilePart {
  std::vector<std::uint32_t> raw_count, segment_count;
  std::vector<RawSample> raws;
  std::vector<PartSegment> segments;
};

// A tile's working storage, one per thread, kept from frame to frame.
struct TileScratch {
  std::vector<RayState> rays;
  std::vector<glm::dvec3> dirs;  // view_ray per pixel
  // Adaptive sampling: per pixel its bundle; per bundle of one support, the samples its plans
  // take (TileMarch::sparse_bundles).
  std::vector<std::uint8_t> bundle;
  std::array<std::int32_t, (kTile / kBundle) * (kTile / kBundle)> sparse{}, sparse_end{};
  std::vector<std::int64_t> needed;
  std::vector<std::uint32_t> walked;  // the supports the march walked (occlusion culling)
  std::vector<double> a, inv_a;       // |view_ray|^2 and its inverse per pixel
  // One row of one support (chord_row): per pixel the depth nearest the centre, the squared
  // distance of the ray from the centre there, and the chord's half length in depth squared.
  double zc[kTile], m2[kTile], h2[kTile];
  std::vector<double> sum, weight;  // the pending samples: window per pixel, a ring
  std::vector<FieldSums> hit_sums;  // light: per pixel and hit
  // A rank's part: per pixel its shared samples' sums and its segments.
  std::vector<std::vector<RawSample>> raws;
  std::vector<std::vector<LocalSegment>> segments;
  TilePlanner planner;  // adaptive sampling: the tile's cells' plans
};

// A tile's plans for another march (VolumeCaster::setup): its bundles not at full rate (their
// positions in the frame, row-major) and their cells, `per_bundle` each, as GpuPlans' words
// whose super-pixels count from the tile's first.
struct TileCells {
  std::vector<std::uint32_t> bundles;
  std::vector<std::uint32_t> cells;
  std::vector<std::array<float, 4>> super_pixels;
  std::size_t per_bundle = 0;
};

}  // namespace

struct VolumeCaster::Work {
  std::vector<Support> supports;      // in view, in input order
  std::vector<std::uint64_t> keys;    // (first - base) << 32 | position in `supports`
  std::vector<std::uint32_t> sorted;  // positions in `supports`, nearest first
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

namespace {

// Project: each valid particle's support in view space, culled where it meets no pixel centre
// or no sample; `counts` gets the invalid and the culled.
void project(const PerspectiveGrid& view_grid, const Samples& s,
             std::span<const VolumeParticle> particles, double support, VolumeCounts& counts,
             std::vector<Support>& out) {
  const ViewFrame& f = view_grid.view();
  out.assign(particles.size(), Support{});
  tbb::combinable<std::array<std::int64_t, 2>> tally([] { return std::array<std::int64_t, 2>{}; });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, particles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::array<std::int64_t, 2>& t = tally.local();
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const VolumeParticle& p = particles[i];
                        Support& o = out[i];
                        if (!drawable(p)) {
                          ++t[0];
                          continue;
                        }
                        o.c = f.to_view(glm::dvec3(p.x, p.y, p.z));
                        o.radius = support * p.h;
                        o.rect = view_grid.sphere_pixels(o.c, o.radius);
                        const double lo = std::max(o.c.z - o.radius, s.near);
                        const double hi = o.c.z + o.radius;
                        if (o.rect.empty() || !(hi > lo)) {
                          o.rect = {};  // not binned
                          ++t[1];
                          continue;
                        }
                        o.first = s.lattice.first_at_or_after(lo);
                        o.last = s.lattice.last_at_or_before(hi);
                        o.first_depth = s.lattice.depth(o.first);
                        o.per_depth = 1 / (s.lattice.k * o.first_depth);
                        if (o.last < o.first) {
                          o.rect = {};
                          ++t[1];
                          continue;
                        }
                        o.inv_h = 1 / double(p.h);
                        o.v = double(p.weight);
                        o.vq = o.v * double(p.value);
                      }
                    });
  tally.combine_each([&](const std::array<std::int64_t, 2>& t) {
    counts.particles_invalid += t[0];
    counts.particles_culled += t[1];
  });
}

// Sort: the supports in view, nearest first sample first, ties by input order.
void sort_supports(const std::vector<Support>& supports, std::int64_t base,
                   std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& sorted) {
  keys.clear();
  for (std::size_t i = 0; i < supports.size(); ++i)
    if (!supports[i].rect.empty())
      keys.push_back(std::uint64_t(supports[i].first - base) << 32 | std::uint64_t(i));
  tbb::parallel_sort(keys.begin(), keys.end());
  sorted.resize(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k) sorted[k] = std::uint32_t(keys[k] & 0xffffffffu);
}

// Bin: per tile the supports whose rectangles touch it, in the sorted order.
void bin_supports(const Tiles& screen, const std::vector<Support>& supports,
                  std::span<const std::uint32_t> sorted, Bins& bins,
                  std::vector<std::uint32_t>& lists) {
  const auto tiles_of = [&](std::size_t k, auto&& f) { screen.each(supports[sorted[k]].rect, f); };
  bins.count(screen.count(), sorted.size(), tiles_of);
  lists.resize(bins.size());
  bins.place(tiles_of, [&](std::size_t k, std::uint32_t slot) { lists[slot] = sorted[k]; });
}

// The kernel of support s at the n samples of depths z[k] on the ray of |d|^2 = a whose depth
// nearest s's centre is zc, at distance^2 m2 from it (|z d - c|^2 = a (z - zc)^2 + m2, which
// keeps its precision at any distance), added to sum[k] (V q W) and weight[k] (V W). No branch:
// it vectorizes, with AVX2 where the processor has it (the same IEEE operations either way, so
// the same sums).
template <SphKernel K>
__attribute__((target_clones("avx2", "default"))) void add_kernel(
    const double* __restrict z, std::int64_t n, double zc, double a, double m2, const Support& s,
    double* __restrict sum, double* __restrict weight) {
  const double inv_h = s.inv_h, vq = s.vq, v = s.v;
  for (std::int64_t k = 0; k < n; ++k) {
    const double t = z[k] - zc;
    const double shape = kernel_shape<K>(std::sqrt(a * t * t + m2) * inv_h);
    sum[k] += vq * shape;
    weight[k] += v * shape;
  }
}

// Support s's part of the field's sums and their gradients at view point x (an iso hit's).
template <SphKernel K> void add_field_sums(glm::dvec3 x, const Support& s, FieldSums& a) {
  const glm::dvec3 d = x - s.c;
  const double dist = std::sqrt(glm::dot(d, d));
  const double q = dist * s.inv_h;
  const double shape = kernel_shape<K>(q);
  if (shape == 0 && q >= kernel_support(K)) return;
  const glm::dvec3 g = dist > 0 ? (kernel_slope<K>(q) * s.inv_h / dist) * d : glm::dvec3(0);
  a.s += s.vq * shape;
  a.w += s.v * shape;
  a.grad_s += s.vq * g;
  a.grad_w += s.v * g;
}

// The march and the light of one tile, for kernel K: of the whole frame, or with kPart of a
// rank's part of it, given `shared` (per pixel, the samples other ranks reach too).
template <SphKernel K, bool kPart> class TileMarch {
 public:
  // `tf`: adaptive sampling's transfer bounds (null: every sample, as always); `cull`: whether
  // the supports behind opaque tiles and bundles are left out (VolumeCaster::set_tile_culling).
  TileMarch(const Samples& s, const VolumeOptions& o, const ViewFrame& f, model::VolumeHost& host,
            TileScratch& scratch, VolumeCounts& tallies, const PixelRanges* shared,
            const TransferBounds* tf, bool cull)
      : s_(s),
        o_(o),
        f_(f),
        host_(host),
        w_(scratch),
        t_(tallies),
        shared_(shared),
        tf_(tf),
        cull_(cull) {}

  void run(const PixelRect& tile, std::span<const std::uint32_t> list,
           const std::vector<Support>& supports, VolumeFrame& out) {
    march(tile, list, supports);
    finish(out);
  }

  void run_part(const PixelRect& tile, std::span<const std::uint32_t> list,
                const std::vector<Support>& supports, TilePart& out) {
    march(tile, list, supports);
    finish_part(out);
  }

  // The tile's plans for a march summing in float (VolumeCaster::setup), into `out`.
  void plan_for_float_sums(const PixelRect& tile, std::span<const std::uint32_t> list,
                           const std::vector<Support>& supports, TileCells& out) {
    tile_ = tile;
    out.bundles.clear();
    out.cells.clear();
    out.super_pixels.clear();
    if (list.empty() || !plan_cells(list, supports, o_.weight_floor * (1 + kFloatSumsMargin)))
      return;
    const TilePlanner& planner = w_.planner;
    const int frame_bundles_x = (f_.width + kBundle - 1) / kBundle;
    out.per_bundle = std::size_t(planner.cells());
    for (int b = 0; b < planner.bundles(); ++b) {
      if (planner.full_rate(b)) continue;
      const int x = tile.x0 / kBundle + b % planner.bundles_x();
      const int y = tile.y0 / kBundle + b / planner.bundles_x();
      out.bundles.push_back(std::uint32_t(x + y * frame_bundles_x));
      for (std::int64_t c = 0; c < planner.cells(); ++c) {
        const CellPlan& cell = planner.cell(b, (planner.first_cell() + c) << kCellShift);
        std::uint32_t word = cell.level;
        if (cell.level == kSuperPixel) {
          word |= std::uint32_t(out.super_pixels.size()) << GpuPlans::kLevelBits;
          out.super_pixels.push_back(
              {cell.light[0], cell.light[1], cell.light[2], cell.transmittance});
        }
        out.cells.push_back(word);
      }
    }
  }

  // Per pixel of the tile, the hull of the samples the supports reach, into hulls (the frame's).
  void cover(const PixelRect& tile, std::span<const std::uint32_t> list,
             const std::vector<Support>& supports, std::vector<SampleRange>& hulls) {
    start(tile, {}, supports);
    for (std::uint32_t k : list)
      each_chord(supports[k], [&](int p, const Support& s, double, double, double d0, double d1) {
        const std::int64_t i0 = first_sample(s, d0), i1 = last_sample(s, d1);
        if (i1 < i0) return;
        SampleRange& h = hulls[global_pixel(p)];
        if (h.empty()) h = {std::int32_t(i0), std::int32_t(i1)};
        h.first = std::min(h.first, std::int32_t(i0));
        h.last = std::max(h.last, std::int32_t(i1));
      });
  }

 private:
  int width() const { return tile_.x1 - tile_.x0 + 1; }
  std::size_t global_pixel(int p) const {
    return std::size_t(tile_.x0 + p % width()) +
           std::size_t(tile_.y0 + p / width()) * std::size_t(f_.width);
  }

  void march(const PixelRect& tile, std::span<const std::uint32_t> list,
             const std::vector<Support>& supports) {
    start(tile, list, supports);
    plan_ = nullptr;
    if (tf_ != nullptr && !list.empty()) plan(list, supports);
    add_until_opaque(list, supports);
    for (int p = 0; p < pixels_; ++p) {
      // Up to its last sample, or past its bundle's last super-pixel.
      std::int64_t end = w_.rays[std::size_t(p)].last + 1;
      if (plan_ != nullptr && w_.bundle[std::size_t(p)] != kFullRate)
        end = std::max(end, plan_->super_pixels_end(w_.bundle[std::size_t(p)]));
      flush(p, end);
      if constexpr (kPart) close(p);
    }
    if (has_hits_) light(w_.walked, supports);
  }

  // The tile's supports into its rays in order, those behind opaque rays left out ([FAW10] sec.
  // 5.2's occlusion culling, at the grain of the tile and of its bundles of kBundle^2 rays): once
  // all the tile's rays are opaque its remaining supports, and a support whose pixels' bundles
  // are all opaque, are not walked (each would add to no ray); the walked ones into
  // w_.walked, for the light. Nor are they needed there: a ray composites its samples before
  // the next support's first, and each later support starts at or after that, so none reaches
  // a composited sample or an iso hit between two of them. A ray is composited only when a
  // support crossing it comes, so every kSweepSamples of depth all are brought up to the next
  // support (the same samples in the same order, whenever), for the opaque ones to be seen.
  void add_until_opaque(std::span<const std::uint32_t> list, const std::vector<Support>& supports) {
    w_.walked.clear();
    std::int64_t sweep_at = std::numeric_limits<std::int64_t>::min();
    for (std::size_t n = 0; n < list.size(); ++n) {
      const Support& s = supports[list[n]];
      if (cull_ && s.first >= sweep_at) {
        sweep(s.first);
        sweep_at = s.first + kSweepSamples;
      }
      if (cull_ && done_ == pixels_) {
        ++t_.tiles_culled;
        t_.supports_culled += std::int64_t(list.size() - n);
        return;
      }
      if (cull_ && behind_opaque_bundles(s)) {
        ++t_.supports_culled;
        continue;
      }
      add(s);
      w_.walked.push_back(list[n]);
    }
  }

  // Whether every bundle of the tile that support s's pixels touch has only opaque rays.
  bool behind_opaque_bundles(const Support& s) const {
    const int x0 = std::max(s.rect.x0, tile_.x0) - tile_.x0,
              x1 = std::min(s.rect.x1, tile_.x1) - tile_.x0;
    const int y0 = std::max(s.rect.y0, tile_.y0) - tile_.y0,
              y1 = std::min(s.rect.y1, tile_.y1) - tile_.y0;
    for (int by = y0 / kBundle; by <= y1 / kBundle; ++by)
      for (int bx = x0 / kBundle; bx <= x1 / kBundle; ++bx) {
        const std::size_t b = std::size_t(bx + by * kBundlesX);
        if (bundle_done_[b] < bundle_pixels_[b]) return false;
      }
    return true;
  }
  // The bundle of pixel p of the tile (row-major in the tile), kBundlesX to a row.
  int bundle_at(int p) const {
    return (p % width()) / kBundle + (p / width()) / kBundle * kBundlesX;
  }

  // Every ray that some support has reached composited up to sample `upto`.
  void sweep(std::int64_t upto) {
    for (int p = 0; p < pixels_; ++p)
      if (w_.rays[std::size_t(p)].front != std::numeric_limits<std::int64_t>::min()) flush(p, upto);
  }

  // Adaptive sampling: the tile's cells' plans from its (non-empty) list of supports into
  // w_.planner (render/cpu/volume_adaptive.h), a sample proven defined where the weight's lower
  // bound is at least `weight_floor`; false where the supports reach no sample.
  bool plan_cells(std::span<const std::uint32_t> list, const std::vector<Support>& supports,
                  double weight_floor) {
    std::int64_t hi = supports[list.front()].last;  // the list starts at its first sample
    for (std::uint32_t k : list) hi = std::max(hi, supports[k].last);
    if (hi < supports[list.front()].first) return false;
    TilePlanner& planner = w_.planner;
    planner.start(tile_, supports[list.front()].first, hi, f_, s_.lattice, weight_floor);
    for (std::uint32_t k : list) {
      const Support& s = supports[k];
      planner.add<K>(s.c, s.inv_h, s.v, s.vq / s.v, s.first, s.last, s.rect);
    }
    const auto behind = [&](int x, int y) {
      return glm::dvec3(background(host_.vx_ray_start(), model::vec3(0.0f), true, x, y));
    };
    if constexpr (kPart) hold_shared(planner);
    if (o_.backdrop != nullptr) hold_walls(planner);
    planner.plan(o_, *tf_, behind, kPart, t_);
    return true;
  }

  // Adaptive sampling: the tile's cells' plans for this march.
  void plan(std::span<const std::uint32_t> list, const std::vector<Support>& supports) {
    const Stopwatch watch;
    const bool planned = plan_cells(list, supports, o_.weight_floor);
    t_.planning_ms += watch.ms();
    if (!planned) return;
    const TilePlanner& planner = w_.planner;
    // A pixel's bundle, or kFullRate where all its cells are at full rate: the march as without
    // a plan there, and without one at all where that holds for the whole tile.
    w_.bundle.resize(std::size_t(pixels_));
    bool any = false;
    for (int p = 0; p < pixels_; ++p) {
      const int b = planner.bundle_of(p);
      const bool full = planner.full_rate(b);
      w_.bundle[std::size_t(p)] = full ? kFullRate : std::uint8_t(b);
      any = any || !full;
    }
    if (any) plan_ = &planner;
  }

  // The cells where rays end at their walls stay at full rate: a coarse sample or a super-pixel
  // there would stand for samples behind the walls.
  void hold_walls(TilePlanner& planner) const {
    for (int y = tile_.y0; y <= tile_.y1; ++y)
      for (int x = tile_.x0; x <= tile_.x1; ++x) {
        const std::int64_t wall = wall_sample(x, y);
        if (wall != std::numeric_limits<std::int64_t>::max())
          planner.hold(planner.bundle_of((x - tile_.x0) + (y - tile_.y0) * width()), wall, wall,
                       TilePlanner::Hold::wall);
      }
  }

  // The first sample behind pixel (x, y)'s walls (none: the largest index).
  std::int64_t wall_sample(int x, int y) const {
    const float wall = o_.backdrop != nullptr ? o_.backdrop->wall_depth(x, y) : Backdrop::kNoWall;
    return wall == Backdrop::kNoWall ? std::numeric_limits<std::int64_t>::max()
                                     : s_.lattice.last_at_or_before(double(wall)) + 1;
  }

  // Pixel (x, y)'s colour: the ray's light over the backdrop, or over the environment.
  glm::vec4 background(const model::VolumeHost::VolumeRay& ray, model::vec3 hits, bool environment,
                       int x, int y) const {
    if (o_.backdrop != nullptr)
      return over_backdrop(*o_.backdrop, x, y, ray.color + hits, ray.transmittance, environment);
    return host_.pixel_color(ray, hits, environment, f_, x, y);
  }

  // A rank's part: the cells holding samples other ranks reach too stay at full rate (their
  // sums are sent, not composited here; render/cpu/volume_adaptive.h).
  void hold_shared(TilePlanner& planner) const {
    for (int p = 0; p < pixels_; ++p)
      for (const SampleRange& r : shared_->of(global_pixel(p)))
        planner.hold(planner.bundle_of(p), r.first, r.last, TilePlanner::Hold::shared);
  }

  void start(const PixelRect& tile, std::span<const std::uint32_t> list,
             const std::vector<Support>& supports) {
    tile_ = tile;
    pixels_ = width() * (tile_.y1 - tile_.y0 + 1);
    done_ = 0;
    bundle_done_.fill(0);
    bundle_pixels_.fill(0);
    for (int p = 0; p < pixels_; ++p) ++bundle_pixels_[std::size_t(bundle_at(p))];
    has_hits_ = false;
    std::int64_t span = 1;
    for (std::uint32_t k : list) span = std::max(span, supports[k].last - supports[k].first + 1);
    window_ = std::int64_t(std::bit_ceil(std::uint64_t(span)));
    mask_ = window_ - 1;
    w_.rays.assign(std::size_t(pixels_), RayState{});
    w_.dirs.resize(std::size_t(pixels_));
    w_.a.resize(std::size_t(pixels_));
    w_.inv_a.resize(std::size_t(pixels_));
    w_.sum.assign(std::size_t(window_) * std::size_t(pixels_), 0.0);
    w_.weight.assign(w_.sum.size(), 0.0);
    if constexpr (kPart) {
      w_.raws.resize(std::size_t(pixels_));
      w_.segments.resize(std::size_t(pixels_));
    }
    for (int p = 0; p < pixels_; ++p) {
      const int x = tile_.x0 + p % width(), y = tile_.y0 + p / width();
      w_.dirs[std::size_t(p)] = f_.view_ray(x, y);
      w_.a[std::size_t(p)] = glm::dot(w_.dirs[std::size_t(p)], w_.dirs[std::size_t(p)]);
      w_.inv_a[std::size_t(p)] = 1 / w_.a[std::size_t(p)];
      RayState& r = w_.rays[std::size_t(p)];
      r.ray = host_.vx_ray_start();
      r.scale = float(glm::length(w_.dirs[std::size_t(p)]));
      r.front = std::numeric_limits<std::int64_t>::min();
      r.wall = wall_sample(x, y);
      if constexpr (kPart) {
        w_.raws[std::size_t(p)].clear();
        w_.segments[std::size_t(p)].clear();
        r.next_shared = shared_->start[global_pixel(p)];
      }
    }
  }

  // f(p, s, zc, m2, d0, d1) for every pixel p of the tile whose ray crosses support s, with the
  // depth nearest its centre, the ray's squared distance from it there (chord_row) and the
  // chord's ends d0 <= d1 (d0 clipped to the near plane), in row order.
  template <class F> void each_chord(const Support& s, F&& f) {
    const int x0 = std::max(s.rect.x0, tile_.x0), x1 = std::min(s.rect.x1, tile_.x1);
    const int y0 = std::max(s.rect.y0, tile_.y0), y1 = std::min(s.rect.y1, tile_.y1);
    for (int y = y0; y <= y1; ++y) {
      const int row = (y - tile_.y0) * width();
      chord_row(s, row + (x0 - tile_.x0), x1 - x0 + 1);
      for (int k = 0; k <= x1 - x0; ++k) {
        if (!(w_.h2[k] > 0)) continue;  // the ray misses the support
        const double half = std::sqrt(w_.h2[k]), zc = w_.zc[k];
        const double d0 = std::max(zc - half, s_.near), d1 = zc + half;
        if (d1 < d0) continue;
        f(row + (x0 - tile_.x0) + k, s, zc, w_.m2[k], d0, d1);
      }
    }
  }

  // One support into every ray of the tile it crosses.
  void add(const Support& s) {
    if (plan_ != nullptr) {
      const Sparse sparse = sparse_bundles(s);
      if (sparse == Sparse::nothing_taken) return;  // super-pixels only: no sample to add to
      if (sparse == Sparse::some) {
        add_sparse(s);
        return;
      }
    }
    each_chord(s, [&](int p, const Support& sp, double zc, double m2, double d0, double d1) {
      add_chord(p, sp, zc, m2, d0, d1);
    });
  }

  // The support's kernel along pixel p's chord [d0, d1], at the samples its cells' plans take.
  void add_chord(int p, const Support& s, double zc, double m2, double d0, double d1) {
    RayState& r = w_.rays[std::size_t(p)];
    if (r.done) return;
    flush(p, s.first);
    if (r.done) return;
    const std::int64_t i0 = first_sample(s, d0), i1 = last_sample(s, d1);
    if (i1 < i0) return;
    t_.kernel_evaluations += accumulate(p, s, w_.a[std::size_t(p)], zc, m2, i0, i1);
    r.last = std::max(r.last, i1);
  }

  // Adaptive sampling: per bundle of the tile that support s reaches, the samples of its range
  // that the bundle's plans take, where no cell of that range is at full rate (w_.sparse: their
  // offsets in w_.needed, -1 for a bundle with a full-rate cell).
  enum class Sparse { none, some, nothing_taken };
  Sparse sparse_bundles(const Support& s) {
    const int x0 = std::max(s.rect.x0, tile_.x0) - tile_.x0,
              x1 = std::min(s.rect.x1, tile_.x1) - tile_.x0;
    const int y0 = std::max(s.rect.y0, tile_.y0) - tile_.y0,
              y1 = std::min(s.rect.y1, tile_.y1) - tile_.y0;
    const int bundles_x = (width() + kBundle - 1) / kBundle;
    w_.needed.clear();
    bool any = false, all = true;
    for (int by = y0 / kBundle; by <= y1 / kBundle; ++by)
      for (int bx = x0 / kBundle; bx <= x1 / kBundle; ++bx) {
        const int b = bx + by * bundles_x;
        const std::size_t begin = w_.needed.size();
        bool sparse = true;
        for (std::int64_t c = s.first >> kCellShift; sparse && c <= s.last >> kCellShift; ++c) {
          const std::uint8_t level = plan_->cell(b, c << kCellShift).level;
          if (level == 0) sparse = false;
          if (level == 0 || level == kSuperPixel) continue;
          const std::int64_t step = std::int64_t(1) << level;
          const std::int64_t end = std::min(s.last, (c << kCellShift) | (kCellSamples - 1));
          for (std::int64_t j = (std::max(s.first, c << kCellShift) + step - 1) & ~(step - 1);
               j <= end; j += step)
            w_.needed.push_back(j);
        }
        if (!sparse) w_.needed.resize(begin);
        w_.sparse[std::size_t(b)] = sparse ? std::int32_t(begin) : -1;
        w_.sparse_end[std::size_t(b)] = std::int32_t(w_.needed.size());
        any = any || sparse;
        all = all && sparse;
      }
    if (all && w_.needed.empty()) return Sparse::nothing_taken;
    return any ? Sparse::some : Sparse::none;
  }

  // Support s into the rays of the tile it crosses, where sparse_bundles() found its samples:
  // the kernel at those samples only (zero outside the support, which adds nothing), without
  // the chord's ends.
  void add_sparse(const Support& s) {
    const int x0 = std::max(s.rect.x0, tile_.x0), x1 = std::min(s.rect.x1, tile_.x1);
    const int y0 = std::max(s.rect.y0, tile_.y0), y1 = std::min(s.rect.y1, tile_.y1);
    const double r2 = s.radius * s.radius;
    for (int y = y0; y <= y1; ++y) {
      const int row = (y - tile_.y0) * width();
      chord_row(s, row + (x0 - tile_.x0), x1 - x0 + 1);
      for (int k = 0; k <= x1 - x0; ++k) {
        if (!(w_.h2[k] > 0)) continue;  // the ray misses the support
        const int p = row + (x0 - tile_.x0) + k;
        const int b = w_.bundle[std::size_t(p)];
        const double zc = w_.zc[k], m2 = w_.m2[k];
        if (b == kFullRate || w_.sparse[std::size_t(b)] < 0) {
          const double half = std::sqrt(w_.h2[k]);
          const double d0 = std::max(zc - half, s_.near), d1 = zc + half;
          if (!(d1 < d0)) add_chord(p, s, zc, m2, d0, d1);
          continue;
        }
        RayState& r = w_.rays[std::size_t(p)];
        if (r.done) continue;
        flush(p, s.first);
        if (r.done) continue;
        const double a = w_.a[std::size_t(p)];
        double* sum = &w_.sum[std::size_t(p) * std::size_t(window_)];
        double* weight = &w_.weight[std::size_t(p) * std::size_t(window_)];
        for (std::int32_t n = w_.sparse[std::size_t(b)]; n < w_.sparse_end[std::size_t(b)]; ++n) {
          const std::int64_t j = w_.needed[std::size_t(n)];
          const double t = s_.depth(j) - zc;
          if (!(a * t * t + m2 < r2)) continue;
          // As add_run's: the same sums as the full-rate march's at this sample.
          add_kernel<K>(&s_.depths[std::size_t(j - s_.base)], 1, zc, a, m2, s, sum + (j & mask_),
                        weight + (j & mask_));
          r.last = std::max(r.last, j);
          ++t_.kernel_evaluations;
        }
      }
    }
  }

  // The support's chords along n pixels of a row from pixel p: the ray z d meets the centre's
  // nearest point at depth zc, at squared distance m2 from it, and |z d - c|^2 = a (z - zc)^2 + m2
  // (which keeps its precision at any distance); the chord is zc -+ sqrt(h2),
  // h2 = (R^2 - m2) / a, none where h2 <= 0. No branch: it vectorizes.
  void chord_row(const Support& s, int p, int n) {
    const double r2 = s.radius * s.radius, cx = s.c.x, cy = s.c.y, cz = s.c.z;
    const glm::dvec3* d = &w_.dirs[std::size_t(p)];
    const double* inv_a = &w_.inv_a[std::size_t(p)];
    for (int k = 0; k < n; ++k) {
      const double zc = (d[k].x * cx + d[k].y * cy + cz) * inv_a[k];
      const double mx = zc * d[k].x - cx, my = zc * d[k].y - cy, mz = zc - cz;
      const double m2 = mx * mx + my * my + mz * mz;
      w_.zc[k] = zc;
      w_.m2[k] = m2;
      w_.h2[k] = (r2 - m2) * inv_a[k];
    }
  }

  // The support's first sample at or after depth d, and its last at or before d: binary searches
  // over its samples without branches (the compiler's conditional moves), a few steps each.
  std::int64_t first_sample(const Support& s, double d) const {
    return s.first + count_below(s, [d](double z) { return z < d; });
  }
  std::int64_t last_sample(const Support& s, double d) const {
    return s.first + count_below(s, [d](double z) { return z <= d; }) - 1;
  }
  // How many of the support's samples, in depth order, `below` holds for (a prefix of them).
  template <class Below> std::int64_t count_below(const Support& s, Below below) const {
    const double* z = &s_.depths[std::size_t(s.first - s_.base)];
    std::int64_t lo = 0, n = s.last - s.first + 1;
    while (n > 0) {
      const std::int64_t half = n / 2;
      const bool right = below(z[lo + half]);
      lo = right ? lo + half + 1 : lo;
      n = right ? n - half - 1 : half;
    }
    return lo;
  }

  // The support's kernel at samples i0..i1 of pixel p's ray, those its cells' plans take, into
  // its pending sums; how many.
  std::int64_t accumulate(int p, const Support& s, double a, double zc, double m2, std::int64_t i0,
                          std::int64_t i1) {
    if (plan_ == nullptr || w_.bundle[std::size_t(p)] == kFullRate) {
      add_run(p, s, a, zc, m2, i0, i1);
      return i1 - i0 + 1;
    }
    const int bundle = w_.bundle[std::size_t(p)];
    std::int64_t n = 0;
    for (std::int64_t i = i0; i <= i1;) {
      const std::int64_t end = std::min(i1, (i | (kCellSamples - 1)));
      const std::uint8_t level = plan_->cell(bundle, i).level;
      if (level == 0) {
        add_run(p, s, a, zc, m2, i, end);
        n += end - i + 1;
      } else if (level != kSuperPixel) {
        const std::int64_t step = std::int64_t(1) << level;
        for (std::int64_t j = (i + step - 1) & ~(step - 1); j <= end; j += step, ++n)
          add_run(p, s, a, zc, m2, j, j);
      }
      i = end + 1;
    }
    return n;
  }

  // The support's kernel at samples i0..i1 of pixel p's ray into its pending sums: the ring's
  // slots in at most two runs.
  void add_run(int p, const Support& s, double a, double zc, double m2, std::int64_t i0,
               std::int64_t i1) {
    double* sum = &w_.sum[std::size_t(p) * std::size_t(window_)];
    double* weight = &w_.weight[std::size_t(p) * std::size_t(window_)];
    const double* z = &s_.depths[std::size_t(i0 - s_.base)];
    std::int64_t i = i0;
    while (i <= i1) {
      const std::int64_t slot = i & mask_;
      const std::int64_t n = std::min(i1 - i + 1, window_ - slot);  // up to the ring's end
      add_kernel<K>(z + (i - i0), n, zc, a, m2, s, sum + slot, weight + slot);
      i += n;
    }
  }

  // Composites pixel p's samples before `upto`: no later support reaches them.
  void flush(int p, std::int64_t upto) {
    RayState& r = w_.rays[std::size_t(p)];
    if (r.done) return;
    const int bundle = plan_ != nullptr ? w_.bundle[std::size_t(p)] : kFullRate;
    const TilePlanner* plan = bundle == kFullRate ? nullptr : plan_;
    // The next sample of a super-pixel cell (adaptive sampling): every ray of its bundle takes
    // it, whether or not a support was added to the ray there.
    const auto next_super_pixel = [&](std::int64_t i) {
      return plan != nullptr ? plan->next_super_pixel(bundle, i)
                             : std::numeric_limits<std::int64_t>::max();
    };
    if (r.front == std::numeric_limits<std::int64_t>::min())  // its first support
      r.front = std::min(upto, next_super_pixel(r.front));
    double* sum = &w_.sum[std::size_t(p) * std::size_t(window_)];
    double* weight = &w_.weight[std::size_t(p) * std::size_t(window_)];
    host_.record_into(&r.hits);
    for (; r.front < upto; ++r.front) {
      if (r.front >= r.wall) {
        end_at_wall(p);
        return;
      }
      if (r.front > r.last) {  // no support reaches the samples up to `upto`
        const std::int64_t next = next_super_pixel(r.front);
        if (next < upto) {
          // A part's segment ends before the samples passed over: other ranks' may lie there.
          if constexpr (kPart)
            if (next > r.front) close(p);
          r.front = next;
        } else {  // the ray leaves the field
          r.ray.defined = 0u;
          r.front = upto;
          if constexpr (kPart) close(p);
          break;
        }
      }
      const std::size_t slot = std::size_t(r.front & mask_);
      const double s = sum[slot], w = weight[slot];
      sum[slot] = weight[slot] = 0;
      if (kPart && shared(p, r, r.front)) {
        close(p);
        if (w > 0) w_.raws[std::size_t(p)].push_back({std::int32_t(r.front), s, w});
        continue;
      }
      const CellPlan* cell = plan != nullptr ? &plan->cell(bundle, r.front) : nullptr;
      const bool super = cell != nullptr && cell->level == kSuperPixel;
      if (kPart && r.open < 0) {
        // A segment starts at a sample some particle reaches: one before this rank's first on
        // the ray (the march starts at its supports' first samples over their whole spheres)
        // may lie among another rank's samples, and no particle reaches it. A super-pixel cell
        // holds no other rank's sample and is defined at every ray of its bundle.
        if (!(w > 0) && !super) continue;
        open(p, r.front);
      }
      std::int64_t span = 1;
      if (cell != nullptr) {
        if (super) {
          super_pixel(p, r, *cell);
          if (r.done) return;
          continue;
        }
        span = std::int64_t(1) << cell->level;
        if ((r.front & (span - 1)) != 0) {
          ++t_.samples_skipped;  // its run's first sample stood for it
          continue;
        }
      }
      composite(p, r, r.front, s, w, span);
      if (r.done) return;
    }
  }

  // Whether sample i of pixel p's ray is one other ranks reach too (i grows along the ray).
  bool shared(int p, RayState& r, std::int64_t i) const {
    const std::uint32_t end = shared_->start[global_pixel(p) + 1];
    while (r.next_shared < end && shared_->ranges[r.next_shared].last < i) ++r.next_shared;
    return r.next_shared < end && shared_->ranges[r.next_shared].first <= i;
  }

  // A segment of pixel p's ray from sample i: the ray composited afresh from transmittance 1.
  void open(int p, std::int64_t i) {
    RayState& r = w_.rays[std::size_t(p)];
    std::vector<LocalSegment>& segments = w_.segments[std::size_t(p)];
    r.open = int(segments.size());
    r.ray = host_.vx_ray_start();
    r.unlit_at_open = r.hits.unlit;
    LocalSegment& seg = segments.emplace_back();
    seg.out.first = seg.out.last = std::int32_t(i);
    seg.hit_begin = seg.hit_end = r.hits.count;
  }

  // Ends pixel p's open segment, if any, where the ray is.
  void close(int p) {
    RayState& r = w_.rays[std::size_t(p)];
    if (r.open < 0) return;
    LocalSegment& seg = w_.segments[std::size_t(p)][std::size_t(r.open)];
    seg.out.q_last = r.ray.q;
    if (r.ray.defined == 1u) seg.out.flags |= PartSegment::kLastDefined;
    if (r.done) seg.out.flags |= PartSegment::kStopped;
    seg.out.color = r.ray.color + (r.hits.unlit - r.unlit_at_open);
    seg.out.transmittance = r.ray.transmittance;
    seg.hit_end = r.hits.count;
    r.open = -1;
  }

  // Sample i of ray r (with adaptive sampling: standing for `span` samples from i).
  void composite(int p, RayState& r, std::int64_t i, double s, double w, std::int64_t span = 1) {
    const bool defined = w > 0 && (!o_.shepard || w >= o_.weight_floor);
    const double q = !defined ? 0.0 : o_.shepard ? s / w : s;
    t_.samples += defined ? 1 : 0;
    const double z = s_.depth(i);
    double extent = s_.lattice.extent(z);
    for (std::int64_t j = 1; j < span; ++j) extent += s_.lattice.extent(s_.depth(i + j));
    const float length = float(extent * r.scale);
    const float before = r.ray.transmittance;
    const int hits = r.hits.count + r.hits.unlit_count;
    r.ray = host_.vx_sample(r.ray, float(q), defined ? 1u : 0u, float(z), length);
    const int new_hits = r.hits.count + r.hits.unlit_count - hits;
    if (new_hits > 0) {
      t_.iso_hits += new_hits;
      has_hits_ = true;
      if (r.first_depth == 0 && r.hits.count > 0) {
        r.first_depth = r.hits.hit[0].depth * r.scale;
        r.first_is_hit = true;
      }
    }
    const bool half = before >= 0.5f && r.ray.transmittance < 0.5f;
    if (r.first_depth == 0 && half) r.first_depth = float(z * r.scale);
    if constexpr (kPart) {
      PartSegment& seg = w_.segments[std::size_t(p)][std::size_t(r.open)].out;
      if (i == seg.first) {
        seg.q_first = r.ray.q;
        if (defined) seg.flags |= PartSegment::kFirstDefined;
      }
      seg.last = std::int32_t(i);
      if (seg.half_depth == 0 && half) seg.half_depth = float(z * r.scale);
    }
    if (r.ray.transmittance < o_.termination) stop(p);
  }

  // Ray r enters a super-pixel cell: its light and transmittance, once.
  void super_pixel(int p, RayState& r, const CellPlan& cell) {
    ++t_.samples_skipped;
    if constexpr (kPart)
      w_.segments[std::size_t(p)][std::size_t(r.open)].out.last = std::int32_t(r.front);
    const std::int64_t at = r.front >> kCellShift;
    if (r.super_cell == at) return;
    r.super_cell = at;
    const float before = r.ray.transmittance;
    r.ray.color += before * model::vec3(cell.light[0], cell.light[1], cell.light[2]);
    r.ray.transmittance *= cell.transmittance;
    r.ray.defined = 1u;
    if (r.first_depth == 0 && before >= 0.5f && r.ray.transmittance < 0.5f)
      r.first_depth = float(s_.lattice.depth((at << kCellShift) + kCellSamples / 2) * r.scale);
    if (r.ray.transmittance < o_.termination) stop(p);
  }

  // Pixel p's ray is opaque: it takes no more samples (its segment closed as stopped, which
  // ends the composited ray there).
  void stop(int p) {
    end_ray(p);
    ++t_.rays_stopped;
    if constexpr (kPart) close(p);
  }

  // Pixel p's ray is at its walls: no rank has samples behind them.
  void end_at_wall(int p) {
    if constexpr (kPart) close(p);
    end_ray(p);
  }

  void end_ray(int p) {
    w_.rays[std::size_t(p)].done = true;
    ++done_;
    ++bundle_done_[std::size_t(bundle_at(p))];
  }

  // The iso hits' gradients from the tile's supports, then their light.
  void light(std::span<const std::uint32_t> list, const std::vector<Support>& supports) {
    const std::size_t per_pixel = std::size_t(model::kMaxIsoHits);
    w_.hit_sums.assign(per_pixel * std::size_t(pixels_), FieldSums{});
    for (std::uint32_t k : list) {
      const Support& s = supports[k];
      const int x0 = std::max(s.rect.x0, tile_.x0), x1 = std::min(s.rect.x1, tile_.x1);
      const int y0 = std::max(s.rect.y0, tile_.y0), y1 = std::min(s.rect.y1, tile_.y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const int p = (x - tile_.x0) + (y - tile_.y0) * width();
          const RayState& r = w_.rays[std::size_t(p)];
          for (int h = 0; h < r.hits.count; ++h)
            add_field_sums<K>(double(r.hits.hit[std::size_t(h)].depth) * w_.dirs[std::size_t(p)], s,
                              w_.hit_sums[std::size_t(p) * per_pixel + std::size_t(h)]);
        }
    }
    for (int p = 0; p < pixels_; ++p) {
      RayState& r = w_.rays[std::size_t(p)];
      const int x = tile_.x0 + p % width(), y = tile_.y0 + p / width();
      const glm::dvec3& dir = w_.dirs[std::size_t(p)];
      for (int h = 0; h < r.hits.count; ++h) {
        model::IsoHit& hit = r.hits.hit[std::size_t(h)];
        const FieldSums& sums = w_.hit_sums[std::size_t(p) * per_pixel + std::size_t(h)];
        host_.refine_hit(hit, sums, dir, o_.shepard, s_.lattice.k * double(hit.depth));
        const model::vec3 light = host_.hit_light(hit, field_gradient(sums, o_.shepard), f_, x, y);
        if constexpr (!kPart) {
          r.ray.color += light;
          continue;
        }
        for (LocalSegment& seg : w_.segments[std::size_t(p)])
          if (h >= seg.hit_begin && h < seg.hit_end) {
            seg.out.color += light;
            if (h == seg.hit_begin) seg.out.hit_depth = hit.depth * r.scale;
          }
      }
      if (r.first_is_hit) r.first_depth = r.hits.hit[0].depth * r.scale;
    }
  }

  void finish(VolumeFrame& out) {
    for (int p = 0; p < pixels_; ++p) {
      const RayState& r = w_.rays[std::size_t(p)];
      const int x = tile_.x0 + p % width(), y = tile_.y0 + p / width();
      out.picture.set(x, y, background(r.ray, r.hits.unlit, o_.background, x, y));
      out.depth[std::size_t(x) + std::size_t(y) * std::size_t(out.picture.width)] = r.first_depth;
      t_.iso_hits_unlit += r.hits.unlit_count;
    }
  }

  void finish_part(TilePart& out) {
    out.raw_count.resize(std::size_t(pixels_));
    out.segment_count.resize(std::size_t(pixels_));
    out.raws.clear();
    out.segments.clear();
    for (int p = 0; p < pixels_; ++p) {
      const std::vector<RawSample>& raws = w_.raws[std::size_t(p)];
      const std::vector<LocalSegment>& segments = w_.segments[std::size_t(p)];
      out.raw_count[std::size_t(p)] = std::uint32_t(raws.size());
      out.segment_count[std::size_t(p)] = std::uint32_t(segments.size());
      out.raws.insert(out.raws.end(), raws.begin(), raws.end());
      for (const LocalSegment& seg : segments) out.segments.push_back(seg.out);
      t_.iso_hits_unlit += w_.rays[std::size_t(p)].hits.unlit_count;
    }
  }

  const Samples& s_;
  const VolumeOptions& o_;
  const ViewFrame& f_;
  model::VolumeHost& host_;
  TileScratch& w_;
  VolumeCounts& t_;
  const PixelRanges* shared_;
  const TransferBounds* tf_;
  static constexpr int kBundlesX = kTile / kBundle;
  const bool cull_;
  const TilePlanner* plan_ = nullptr;
  PixelRect tile_;
  int pixels_ = 0, done_ = 0;  // the tile's pixels, and its rays that stopped
  // Per bundle of the tile (kBundlesX to a row): its pixels, and its rays that stopped.
  std::array<int, kBundlesX * kBundlesX> bundle_pixels_{}, bundle_done_{};
  std::int64_t window_ = 1, mask_ = 0;
  bool has_hits_ = false;
};

}  // namespace

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
  project(view_grid, s, particles, support, counts, w.supports);
  lap(VolumeCastPhase::project);

  std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = lo;
  hi = std::numeric_limits<std::int64_t>::min();
  for (const Support& p : w.supports)
    if (!p.rect.empty()) lo = std::min(lo, p.first), hi = std::max(hi, p.last);
  if (hi < lo) lo = hi = 0;
  for (const Support& p : w.supports)
    if (!p.rect.empty() && p.last - p.first + 1 > kMaxSupportSamples)
      throw make_error("a particle's support spans ", p.last - p.first + 1,
                       " samples along the view (at most ", kMaxSupportSamples,
                       "): a smoothing length far above the particle spacing, or a particle "
                       "around the eye; coarsen `sampling` or move the camera");
  s.base = lo;
  s.depths.resize(std::size_t(hi - lo + 2));
  for (std::size_t k = 0; k < s.depths.size(); ++k)
    s.depths[k] = s.lattice.depth(lo + std::int64_t(k));
  sort_supports(w.supports, s.base, w.keys, w.sorted);
  lap(VolumeCastPhase::sort);

  bin_supports(Tiles(camera.width, camera.height, kTile), w.supports, w.sorted, w.tile_bins,
               w.tile_lists);
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
  // The supports in view in their sorted order, and the tiles' lists in those positions.
  std::vector<std::uint32_t> position(w.supports.size(), 0);
  out.supports.resize(w.sorted.size());
  for (std::size_t k = 0; k < w.sorted.size(); ++k) {
    const Support& s = w.supports[w.sorted[k]];
    position[w.sorted[k]] = std::uint32_t(k);
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
  out.tile_lists.resize(w.tile_lists.size());
  for (std::size_t k = 0; k < w.tile_lists.size(); ++k)
    out.tile_lists[k] = position[w.tile_lists[k]];
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
