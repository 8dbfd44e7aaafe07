// render/cpu/volume_rays.h - a screen tile's rays as the CPU volume march composites them
// (render/cpu/volume_caster.h's march phase, [FAW10] sec. 4-5): each ray's pending samples, its
// compositing front to back by render/model/volume.glsl (model::VolumeHost), its early stop, its
// iso hits lit, and what it leaves: a picture's pixels, or with kPart a rank's part of them
// (render/volume_parts.h: its segments and its sums at the samples other ranks reach too).
//
// Reads the sums that render/cpu/volume_march.h adds to each ray's pending samples (a ring of
// `window` samples per pixel), the tile's adaptive plans (render/cpu/volume_adaptive.h) and the
// walls' backdrop; writes a VolumeFrame's pixels or a TilePart. Cost: per composited sample one
// transfer-function look-up and blend; per iso hit one Newton step and its light.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "render/backdrop.h"
#include "render/cpu/volume_adaptive.h"
#include "render/cpu/volume_caster.h"
#include "render/cpu/volume_supports.h"
#include "render/model/volume_host.h"
#include "render/volume_parts.h"

namespace voxspan::volume_cast {

constexpr int kTile = VolumeCaster::kTile;
// Per pixel, the mark of a pixel whose bundle is at full rate in every cell.
constexpr std::uint8_t kFullRate = 0xff;
static_assert((kTile / kBundle) * (kTile / kBundle) < kFullRate, "a tile's bundles in a byte");

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

// A tile's rays' storage, one per thread, kept from tile to tile.
struct RayScratch {
  std::vector<RayState> rays;
  std::vector<glm::dvec3> dirs;      // view_ray per pixel
  std::vector<std::uint8_t> bundle;  // adaptive sampling: per pixel its bundle, or kFullRate
  std::vector<double> sum, weight;   // the pending samples: window per pixel, a ring
  std::vector<FieldSums> hit_sums;   // per pixel and iso hit: the field's sums there
  // A rank's part: per pixel its shared samples' sums and its segments.
  std::vector<std::vector<RawSample>> raws;
  std::vector<std::vector<LocalSegment>> segments;
};

// The first sample behind pixel (x, y)'s walls (none: the largest index).
inline std::int64_t wall_sample(const VolumeOptions& o, const VolumeLattice& lattice, int x,
                                int y) {
  const float wall = o.backdrop != nullptr ? o.backdrop->wall_depth(x, y) : Backdrop::kNoWall;
  return wall == Backdrop::kNoWall ? std::numeric_limits<std::int64_t>::max()
                                   : lattice.last_at_or_before(double(wall)) + 1;
}

// The rays of one tile: of the whole frame, or with kPart of a rank's part of it, given `shared`
// (per pixel, the samples other ranks reach too).
template <bool kPart> class TileRays {
 public:
  static constexpr int kBundlesX = kTile / kBundle;

  TileRays(const Samples& s, const VolumeOptions& o, const ViewFrame& f, model::VolumeHost& host,
           RayScratch& scratch, VolumeCounts& tallies, const PixelRanges* shared)
      : s_(s), o_(o), f_(f), host_(host), w_(scratch), t_(tallies), shared_(shared) {}

  // Every ray of `tile` at its start, with a ring of `window` (a power of two) pending samples.
  void start(const PixelRect& tile, std::int64_t window) {
    tile_ = tile;
    pixels_ = width() * (tile_.y1 - tile_.y0 + 1);
    done_ = 0;
    bundle_done_.fill(0);
    bundle_pixels_.fill(0);
    for (int p = 0; p < pixels_; ++p) ++bundle_pixels_[std::size_t(bundle_at(p))];
    has_hits_ = false;
    plan_ = nullptr;
    window_ = window;
    mask_ = window_ - 1;
    w_.rays.assign(std::size_t(pixels_), RayState{});
    w_.dirs.resize(std::size_t(pixels_));
    w_.sum.assign(std::size_t(window_) * std::size_t(pixels_), 0.0);
    w_.weight.assign(w_.sum.size(), 0.0);
    if constexpr (kPart) {
      w_.raws.resize(std::size_t(pixels_));
      w_.segments.resize(std::size_t(pixels_));
    }
    for (int p = 0; p < pixels_; ++p) {
      const int x = tile_.x0 + p % width(), y = tile_.y0 + p / width();
      w_.dirs[std::size_t(p)] = f_.view_ray(x, y);
      RayState& r = w_.rays[std::size_t(p)];
      r.ray = host_.vx_ray_start();
      r.scale = float(glm::length(w_.dirs[std::size_t(p)]));
      r.front = std::numeric_limits<std::int64_t>::min();
      r.wall = wall_sample(o_, s_.lattice, x, y);
      if constexpr (kPart) {
        w_.raws[std::size_t(p)].clear();
        w_.segments[std::size_t(p)].clear();
        r.next_shared = shared_->start[global_pixel(p)];
      }
    }
  }

  // Adaptive sampling: the tile's cells' plans for the rays (kept by the caller while they
  // march); none where every cell of the tile is at full rate.
  void set_plan(const TilePlanner& planner) {
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
  // The plans (null: every sample of every ray) and pixel p's bundle in them, or kFullRate.
  const TilePlanner* plan() const { return plan_; }
  int bundle(int p) const { return plan_ != nullptr ? w_.bundle[std::size_t(p)] : kFullRate; }

  int width() const { return tile_.x1 - tile_.x0 + 1; }
  int pixels() const { return pixels_; }
  std::size_t global_pixel(int p) const {
    return std::size_t(tile_.x0 + p % width()) +
           std::size_t(tile_.y0 + p / width()) * std::size_t(f_.width);
  }
  RayState& ray(int p) { return w_.rays[std::size_t(p)]; }
  const glm::dvec3& dir(int p) const { return w_.dirs[std::size_t(p)]; }
  // Pixel p's pending sums: sample i in slot i & mask() of window() slots.
  double* sum(int p) { return &w_.sum[std::size_t(p) * std::size_t(window_)]; }
  double* weight(int p) { return &w_.weight[std::size_t(p) * std::size_t(window_)]; }
  std::int64_t window() const { return window_; }
  std::int64_t mask() const { return mask_; }

  // Whether every ray of the tile has stopped, and every ray of bundle b (kBundlesX to a row).
  bool all_stopped() const { return done_ == pixels_; }
  bool bundle_stopped(int b) const {
    return bundle_done_[std::size_t(b)] >= bundle_pixels_[std::size_t(b)];
  }

  // Pixel (x, y)'s colour: the ray's light over the backdrop, or over the environment.
  glm::vec4 background(const model::VolumeHost::VolumeRay& ray, model::vec3 hits, bool environment,
                       int x, int y) const {
    if (o_.backdrop != nullptr)
      return over_backdrop(*o_.backdrop, x, y, ray.color + hits, ray.transmittance, environment);
    return host_.pixel_color(ray, hits, environment, f_, x, y);
  }
  // Pixel (x, y)'s light behind the fluid.
  glm::dvec3 behind(int x, int y) const {
    return glm::dvec3(background(host_.vx_ray_start(), model::vec3(0.0f), true, x, y));
  }

  // Composites pixel p's samples before `upto`: no later support reaches them.
  void flush(int p, std::int64_t upto) {
    RayState& r = w_.rays[std::size_t(p)];
    if (r.done) return;
    const int bundle = this->bundle(p);
    const TilePlanner* plan = bundle == kFullRate ? nullptr : plan_;
    // The next sample of a super-pixel cell (adaptive sampling): every ray of its bundle takes
    // it, whether or not a support was added to the ray there.
    const auto next_super_pixel = [&](std::int64_t i) {
      return plan != nullptr ? plan->next_super_pixel(bundle, i)
                             : std::numeric_limits<std::int64_t>::max();
    };
    if (r.front == std::numeric_limits<std::int64_t>::min())  // its first support
      r.front = std::min(upto, next_super_pixel(r.front));
    double* sum = this->sum(p);
    double* weight = this->weight(p);
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

  // Every ray that some support has reached composited up to sample `upto`.
  void sweep(std::int64_t upto) {
    for (int p = 0; p < pixels_; ++p)
      if (w_.rays[std::size_t(p)].front != std::numeric_limits<std::int64_t>::min()) flush(p, upto);
  }

  // Every ray composited to its end: its last sample, or past its bundle's last super-pixel.
  void complete() {
    for (int p = 0; p < pixels_; ++p) {
      std::int64_t end = w_.rays[std::size_t(p)].last + 1;
      if (bundle(p) != kFullRate) end = std::max(end, plan_->super_pixels_end(bundle(p)));
      flush(p, end);
      if constexpr (kPart) close(p);
    }
  }

  // Whether some ray has an iso hit; per pixel p its hits' sums (kMaxIsoHits each), zeroed.
  bool has_hits() const { return has_hits_; }
  FieldSums* clear_hit_sums() {
    w_.hit_sums.assign(std::size_t(model::kMaxIsoHits) * std::size_t(pixels_), FieldSums{});
    return w_.hit_sums.data();
  }
  // The iso hits lit from their sums (clear_hit_sums()' then added to).
  void light() {
    const std::size_t per_pixel = std::size_t(model::kMaxIsoHits);
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

  // The tile's pixels into `out`'s picture and depths.
  void finish(VolumeFrame& out) {
    for (int p = 0; p < pixels_; ++p) {
      const RayState& r = w_.rays[std::size_t(p)];
      const int x = tile_.x0 + p % width(), y = tile_.y0 + p / width();
      out.picture.set(x, y, background(r.ray, r.hits.unlit, o_.background, x, y));
      out.depth[std::size_t(x) + std::size_t(y) * std::size_t(out.picture.width)] = r.first_depth;
      t_.iso_hits_unlit += r.hits.unlit_count;
    }
  }

  // A rank's part: the tile's shared sums and segments into `out`.
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

 private:
  // The bundle of pixel p of the tile (row-major in the tile), kBundlesX to a row.
  int bundle_at(int p) const {
    return (p % width()) / kBundle + (p / width()) / kBundle * kBundlesX;
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
  void composite(int p, RayState& r, std::int64_t i, double s, double w, std::int64_t span) {
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

  const Samples& s_;
  const VolumeOptions& o_;
  const ViewFrame& f_;
  model::VolumeHost& host_;
  RayScratch& w_;
  VolumeCounts& t_;
  const PixelRanges* shared_;
  const TilePlanner* plan_ = nullptr;
  PixelRect tile_;
  int pixels_ = 0, done_ = 0;  // the tile's pixels, and its rays that stopped
  // Per bundle of the tile (kBundlesX to a row): its pixels, and its rays that stopped.
  std::array<int, kBundlesX * kBundlesX> bundle_pixels_{}, bundle_done_{};
  std::int64_t window_ = 1, mask_ = 0;
  bool has_hits_ = false;
};

}  // namespace voxspan::volume_cast
