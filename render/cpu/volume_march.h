// render/cpu/volume_march.h - the CPU volume caster's march of one screen tile
// (render/cpu/volume_caster.h's march phase, [FAW10] sec. 4-5, [HOK16] sec. 4-6): the tile's
// supports, nearest first, each adding its kernel to the pending samples of the rays it crosses
// (render/cpu/volume_rays.h composites them), those behind opaque rays left out; with adaptive
// sampling the tile's cells planned first (render/cpu/volume_adaptive.h) and each support added
// at the samples the plans take; then the iso hits' gradients from the walked supports.
//
// Reads the frame's supports (render/cpu/volume_supports.h) and the tile's list of them; writes
// the tile's pixels (run), a rank's part of them (run_part), its plans for a march summing in
// float (plan_for_float_sums) or its rays' sample hulls (cover). Cost: per ray and support it
// crosses one chord and a kernel evaluation per sample taken; no allocation once the sizes are
// stable (TileScratch, one per thread).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "render/cpu/volume_adaptive.h"
#include "render/cpu/volume_rays.h"
#include "render/cpu/volume_supports.h"
#include "voxspan/stopwatch.h"

namespace voxspan::volume_cast {

// Occlusion culling: how far (samples of depth) a tile's supports advance between two looks at
// whether all its rays are opaque. Each look walks the tile's rays once; a support walks its
// chords' samples.
constexpr std::int64_t kSweepSamples = 8;
// Plans for a march summing in float (VolumeCaster::setup): a sample is proven defined where the
// weight's lower bound is at least the floor times 1 + this, for the float sum of a few hundred
// positive terms (a relative error of at most n 2^-24) to stay at or above the floor.
constexpr double kFloatSumsMargin = 1e-4;

// A tile's plans for another march (VolumeCaster::setup): its bundles not at full rate (their
// positions in the frame, row-major) and their cells, `per_bundle` each, as GpuPlans' words
// whose super-pixels count from the tile's first.
struct TileCells {
  std::vector<std::uint32_t> bundles;
  std::vector<std::uint32_t> cells;
  std::vector<std::array<float, 4>> super_pixels;
  std::size_t per_bundle = 0;
};

// A tile's working storage, one per thread, kept from frame to frame.
struct TileScratch {
  RayScratch rays;
  // Adaptive sampling: per bundle of one support, the samples its plans take (sparse_bundles).
  std::array<std::int32_t, (kTile / kBundle) * (kTile / kBundle)> sparse{}, sparse_end{};
  std::vector<std::int64_t> needed;
  std::vector<std::uint32_t> walked;  // the supports the march walked (occlusion culling)
  std::vector<double> a, inv_a;       // |view_ray|^2 and its inverse per pixel
  // One row of one support (chord_row): per pixel the depth nearest the centre, the squared
  // distance of the ray from the centre there, and the chord's half length in depth squared.
  double zc[kTile], m2[kTile], h2[kTile];
  TilePlanner planner;  // adaptive sampling: the tile's cells' plans
};

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
        w_(scratch),
        t_(tallies),
        shared_(shared),
        tf_(tf),
        cull_(cull),
        rays_(s, o, f, host, scratch.rays, tallies, shared) {}

  void run(const PixelRect& tile, std::span<const std::uint32_t> list,
           const std::vector<Support>& supports, VolumeFrame& out) {
    march(tile, list, supports);
    rays_.finish(out);
  }

  void run_part(const PixelRect& tile, std::span<const std::uint32_t> list,
                const std::vector<Support>& supports, TilePart& out) {
    march(tile, list, supports);
    rays_.finish_part(out);
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
        SampleRange& h = hulls[rays_.global_pixel(p)];
        if (h.empty()) h = {std::int32_t(i0), std::int32_t(i1)};
        h.first = std::min(h.first, std::int32_t(i0));
        h.last = std::max(h.last, std::int32_t(i1));
      });
  }

 private:
  int width() const { return tile_.x1 - tile_.x0 + 1; }
  // Support s's pixels in the tile, relative to its first pixel.
  PixelRect in_tile(const Support& s) const {
    return {std::max(s.rect.x0, tile_.x0) - tile_.x0, std::max(s.rect.y0, tile_.y0) - tile_.y0,
            std::min(s.rect.x1, tile_.x1) - tile_.x0, std::min(s.rect.y1, tile_.y1) - tile_.y0};
  }

  void march(const PixelRect& tile, std::span<const std::uint32_t> list,
             const std::vector<Support>& supports) {
    start(tile, list, supports);
    if (tf_ != nullptr && !list.empty()) plan(list, supports);
    add_until_opaque(list, supports);
    rays_.complete();
    if (rays_.has_hits()) light(w_.walked, supports);
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
        rays_.sweep(s.first);
        sweep_at = s.first + kSweepSamples;
      }
      if (cull_ && rays_.all_stopped()) {
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
    const PixelRect in = in_tile(s);
    for (int by = in.y0 / kBundle; by <= in.y1 / kBundle; ++by)
      for (int bx = in.x0 / kBundle; bx <= in.x1 / kBundle; ++bx)
        if (!rays_.bundle_stopped(bx + by * Rays::kBundlesX)) return false;
    return true;
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
    const auto behind = [&](int x, int y) { return rays_.behind(x, y); };
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
    if (planned) rays_.set_plan(w_.planner);
  }

  // The cells where rays end at their walls stay at full rate: a coarse sample or a super-pixel
  // there would stand for samples behind the walls.
  void hold_walls(TilePlanner& planner) const {
    for (int y = tile_.y0; y <= tile_.y1; ++y)
      for (int x = tile_.x0; x <= tile_.x1; ++x) {
        const std::int64_t wall = wall_sample(o_, s_.lattice, x, y);
        if (wall != std::numeric_limits<std::int64_t>::max())
          planner.hold(planner.bundle_of((x - tile_.x0) + (y - tile_.y0) * width()), wall, wall,
                       TilePlanner::Hold::wall);
      }
  }

  // A rank's part: the cells holding samples other ranks reach too stay at full rate (their
  // sums are sent, not composited here; render/cpu/volume_adaptive.h).
  void hold_shared(TilePlanner& planner) const {
    for (int p = 0; p < rays_.pixels(); ++p)
      for (const SampleRange& r : shared_->of(rays_.global_pixel(p)))
        planner.hold(planner.bundle_of(p), r.first, r.last, TilePlanner::Hold::shared);
  }

  // The tile's rays at their start, with room for the longest support's samples.
  void start(const PixelRect& tile, std::span<const std::uint32_t> list,
             const std::vector<Support>& supports) {
    tile_ = tile;
    std::int64_t span = 1;
    for (std::uint32_t k : list) span = std::max(span, supports[k].last - supports[k].first + 1);
    rays_.start(tile, std::int64_t(std::bit_ceil(std::uint64_t(span))));
    const std::size_t pixels = std::size_t(rays_.pixels());
    w_.a.resize(pixels);
    w_.inv_a.resize(pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
      w_.a[p] = glm::dot(rays_.dir(int(p)), rays_.dir(int(p)));
      w_.inv_a[p] = 1 / w_.a[p];
    }
  }

  // f(p, s, zc, m2, d0, d1) for every pixel p of the tile whose ray crosses support s, with the
  // depth nearest its centre, the ray's squared distance from it there (chord_row) and the
  // chord's ends d0 <= d1 (d0 clipped to the near plane), in row order.
  template <class F> void each_chord(const Support& s, F&& f) {
    const PixelRect in = in_tile(s);
    for (int y = in.y0; y <= in.y1; ++y) {
      const int row = y * width() + in.x0;
      chord_row(s, row, in.x1 - in.x0 + 1);
      for (int k = 0; k <= in.x1 - in.x0; ++k) {
        if (!(w_.h2[k] > 0)) continue;  // the ray misses the support
        const double half = std::sqrt(w_.h2[k]), zc = w_.zc[k];
        const double d0 = std::max(zc - half, s_.near), d1 = zc + half;
        if (d1 < d0) continue;
        f(row + k, s, zc, w_.m2[k], d0, d1);
      }
    }
  }

  // One support into every ray of the tile it crosses.
  void add(const Support& s) {
    if (rays_.plan() != nullptr) {
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
    RayState& r = rays_.ray(p);
    if (r.done) return;
    rays_.flush(p, s.first);
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
    const PixelRect in = in_tile(s);
    const int bundles_x = (width() + kBundle - 1) / kBundle;
    const TilePlanner& plan = *rays_.plan();
    w_.needed.clear();
    bool any = false, all = true;
    for (int by = in.y0 / kBundle; by <= in.y1 / kBundle; ++by)
      for (int bx = in.x0 / kBundle; bx <= in.x1 / kBundle; ++bx) {
        const int b = bx + by * bundles_x;
        const std::size_t begin = w_.needed.size();
        bool sparse = true;
        for (std::int64_t c = s.first >> kCellShift; sparse && c <= s.last >> kCellShift; ++c) {
          const std::uint8_t level = plan.cell(b, c << kCellShift).level;
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
    const PixelRect in = in_tile(s);
    const double r2 = s.radius * s.radius;
    const std::int64_t mask = rays_.mask();
    for (int y = in.y0; y <= in.y1; ++y) {
      const int row = y * width() + in.x0;
      chord_row(s, row, in.x1 - in.x0 + 1);
      for (int k = 0; k <= in.x1 - in.x0; ++k) {
        if (!(w_.h2[k] > 0)) continue;  // the ray misses the support
        const int p = row + k;
        const int b = rays_.bundle(p);
        const double zc = w_.zc[k], m2 = w_.m2[k];
        if (b == kFullRate || w_.sparse[std::size_t(b)] < 0) {
          const double half = std::sqrt(w_.h2[k]);
          const double d0 = std::max(zc - half, s_.near), d1 = zc + half;
          if (!(d1 < d0)) add_chord(p, s, zc, m2, d0, d1);
          continue;
        }
        RayState& r = rays_.ray(p);
        if (r.done) continue;
        rays_.flush(p, s.first);
        if (r.done) continue;
        const double a = w_.a[std::size_t(p)];
        double* sum = rays_.sum(p);
        double* weight = rays_.weight(p);
        for (std::int32_t n = w_.sparse[std::size_t(b)]; n < w_.sparse_end[std::size_t(b)]; ++n) {
          const std::int64_t j = w_.needed[std::size_t(n)];
          const double t = s_.depth(j) - zc;
          if (!(a * t * t + m2 < r2)) continue;
          // As add_run's: the same sums as the full-rate march's at this sample.
          add_kernel<K>(&s_.depths[std::size_t(j - s_.base)], 1, zc, a, m2, s, sum + (j & mask),
                        weight + (j & mask));
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
    const glm::dvec3* d = &rays_.dir(p);
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
  // over its samples, a few steps each. GCC branches on the comparison, and neighbouring rays
  // take the same turns: a form of conditional moves and an index estimated from the
  // lattice's logarithm were both slower (docs/benchmarks.md, "Volume views").
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
    const int bundle = rays_.bundle(p);
    if (bundle == kFullRate) {
      add_run(p, s, a, zc, m2, i0, i1);
      return i1 - i0 + 1;
    }
    std::int64_t n = 0;
    for (std::int64_t i = i0; i <= i1;) {
      const std::int64_t end = std::min(i1, (i | (kCellSamples - 1)));
      const std::uint8_t level = rays_.plan()->cell(bundle, i).level;
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
    double* sum = rays_.sum(p);
    double* weight = rays_.weight(p);
    const double* z = &s_.depths[std::size_t(i0 - s_.base)];
    const std::int64_t window = rays_.window(), mask = rays_.mask();
    std::int64_t i = i0;
    while (i <= i1) {
      const std::int64_t slot = i & mask;
      const std::int64_t n = std::min(i1 - i + 1, window - slot);  // up to the ring's end
      add_kernel<K>(z + (i - i0), n, zc, a, m2, s, sum + slot, weight + slot);
      i += n;
    }
  }

  // The iso hits' gradients from the tile's supports, then their light.
  void light(std::span<const std::uint32_t> list, const std::vector<Support>& supports) {
    const std::size_t per_pixel = std::size_t(model::kMaxIsoHits);
    FieldSums* sums = rays_.clear_hit_sums();
    for (std::uint32_t k : list) {
      const Support& s = supports[k];
      const PixelRect in = in_tile(s);
      for (int y = in.y0; y <= in.y1; ++y)
        for (int x = in.x0; x <= in.x1; ++x) {
          const int p = x + y * width();
          const RayState& r = rays_.ray(p);
          for (int h = 0; h < r.hits.count; ++h)
            add_field_sums<K>(double(r.hits.hit[std::size_t(h)].depth) * rays_.dir(p), s,
                              sums[std::size_t(p) * per_pixel + std::size_t(h)]);
        }
    }
    rays_.light();
  }

  using Rays = TileRays<kPart>;
  const Samples& s_;
  const VolumeOptions& o_;
  const ViewFrame& f_;
  TileScratch& w_;
  VolumeCounts& t_;
  const PixelRanges* shared_;
  const TransferBounds* tf_;
  const bool cull_;
  Rays rays_;
  PixelRect tile_;
};

}  // namespace voxspan::volume_cast
