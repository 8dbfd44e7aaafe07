// render/cpu/volume_adaptive.h - adaptive sampling under an error tolerance ([HOK16] sec. 4-5)
// for the CPU caster's DVR march (render/cpu/volume_caster.h): per cell of a tile's rays, how
// sparsely its samples may be taken so that no channel of any pixel moves from the full-rate
// picture by more than VolumeOptions::adaptive.error_tolerance.
//
// Reads a tile's supports (their values, weights, spheres, first and last samples); writes a
// CellPlan per cell. A cell is a ray bundle of kBundle^2 pixels by kCellSamples lattice samples,
// numbered i >> kCellShift from the lattice index i: cells stay put from frame to frame as the
// samples do. Cost: per support and proof block one lower bound of the weight per sample (4
// corner distances and a kernel, vectorised), per cell 31 transfer-function range look-ups; no
// allocation once the sizes are stable.
//
// The bounds ([HOK16] sec. 4.1-4.2). At sample k of a bundle, the Shepard value S / w is a convex
// combination of the values q_j of the particles reaching it, so it lies in [min q_j, max q_j]
// over the supports whose sphere and pixel rectangle reach the sample (a superset). A run of
// samples whose values lie in [qlo, qhi], of total length L, has transmittance in
// [1 - a(alpha_hi, L), 1 - a(alpha_lo, L)] and light in [c_lo a(alpha_lo, L), c_hi a(alpha_hi, L)]
// (a the opacity over a length; alpha and c the transfer function's ranges over [qlo, qhi]; the
// light of the run is c-weighted 1 - prod (1 - a_k)); so does one sample of the run's value
// standing for the whole length, which is what a coarse cell draws. Level l of a cell takes the
// first sample of each 2^l (one for level kCellShift); its bounds composite the runs'.
//
// The error ([HOK16] sec. 4.3 bounds the spread of a whole bundle; we bound the change). Exchanging
// one cell's exact (I, T) for its adaptive one, with everything in front already exchanged,
// moves a pixel by T_front (dI + dT R_back): at most T_front^hi (w(I) + w(T) R_back^hi) with
// both pairs in the cell's bounds (the super-pixel, the middle of the full-rate bounds: half
// that). Summed over the cells in any order this bounds the whole change; full-rate cells add
// nothing (their samples are the exact picture's). The greedy step ([HOK16] sec. 4.4) walks each
// bundle back to front and gives each cell the cheapest choice (super-pixel, then one sample in
// 16, 8, 4, 2) whose term keeps the sum within the tolerance, less a reserve for the float
// compositing's rounding and, where a ray may stop early, 2 termination x the brightest light
// (the full-rate and the adaptive ray may stop at different samples). With relax 0 a coarse
// level never fits where the super-pixel does not: its bounds hold the full-rate ones, whose half
// width is the super-pixel's term; so relax 0 chooses between full rate and super-pixels only.
// AdaptiveOptions::rules leaves parts of this out ([HOK16] Table 2's variants, for benchmarks).
//
// Surface rule ([HOK16] sec. 4.2): a cell where some sample is reached by a support but not
// proven to hold a weight of at least weight_floor at every pixel (a lower bound from each
// support's farthest bundle corner) may be empty at some pixels: it stays at full rate.
//
// relax r in (0, 1] subtracts r times the full-rate bound widths from the coarse levels' ([HOK16]
// sec. 5.1: the full-rate width is the bundle's lateral spread, not a sampling error); super-pixels
// are never relaxed (sec. 5.2: their error is the lateral spread). r = 0: the guarantee.
//
// A rank's part (render/volume_parts.h: its segments, composited with other ranks' segments and
// the shared samples by the merge). The argument above holds over the cells of all ranks taken
// together, front to back along the composited ray, if each cell's term bounds its own exchange
// there: the transmittance in front is at most the product of the rank's own cells' (the others'
// samples only lower it), and the light behind any cell, a composite of samples and background
// whose weights sum to at most 1, is at most M = max(brightest light of the transfer function,
// brightest background) per channel, which the part's plan takes as R_back for every cell. The
// cells holding a sample another rank reaches too (its sums are not this rank's alone, so its
// bounds are not these) are held at full rate. The ranks' terms then add up: each rank spends
// at most `share` (1 / ranks) of the tolerance less the reserves, and the rounding and the early
// stop (which may end the composited ray at any rank's sample: always reserved) are reserved
// once, so the composited picture moves from the full-rate composite by at most the tolerance.
//
// Walls (VolumeOptions::backdrop): a ray ends at its pixel's walls, inside some cell. That cell
// stays at full rate for the whole bundle (a coarse sample or a super-pixel would stand for
// samples behind the walls), with bounds I in [0, I_hi], T in [T_lo, 1] (from none of its samples
// to all of them): the light behind an earlier cell, that cell's then the walls' colour (at most
// the background's brightest), stays within the recurrence's bound; the cells behind the walls
// add nothing to that pixel in either picture.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "render/camera.h"
#include "render/perspective_grid.h"
#include "render/sph_kernel.h"
#include "render/volume.h"

namespace voxspan {

inline constexpr int kBundle = 8;
// The weight's lower bound is taken over blocks this wide: over a whole bundle (2 to 3 particle
// spacings at common sizes) the farthest corner lies past most supports and proves nothing.
inline constexpr int kProofBlock = 4;
inline constexpr int kCellShift = 4;
inline constexpr int kCellSamples = 1 << kCellShift;
inline constexpr std::uint8_t kSuperPixel = kCellShift + 1;

// The share of the tolerance kept for the float compositing's rounding, which the bounds (in
// double) do not see: both pictures round over hundreds of samples.
inline constexpr double kRoundingReserve = 1e-5;

// How a bundle's rays sample one cell.
struct CellPlan {
  // 0: every sample; l in 1..kCellShift: the first of each 2^l, standing for all 2^l;
  // kSuperPixel: none, the cell's light and transmittance below for every ray.
  std::uint8_t level = 0;
  float light[3] = {0, 0, 0};  // premultiplied
  float transmittance = 1;
};

// The transfer function's ranges over value ranges, as the compositing (float) reads the table.
class TransferBounds {
 public:
  struct Range {
    double c_lo[3], c_hi[3];  // colour per channel
    double alpha_lo, alpha_hi;
  };
  explicit TransferBounds(const VolumeOptions& o);
  Range over(double q_lo, double q_hi) const;
  double brightest(int channel) const { return brightest_[std::size_t(channel)]; }
  // a(alpha, length): the opacity of `length` world units (volume.glsl's vx_length_opacity).
  double opacity(double alpha, double length) const;

 private:
  static constexpr int kLevels = 9;  // 2^8 = kTransferEntries
  bool log_;
  double lo_, scale_, inv_length_;
  // Per level j and entry k: the lowest and highest of entries k .. k + 2^j - 1, per channel
  // (r, g, b, alpha).
  std::array<std::array<std::array<double, 8>, kTransferEntries>, kLevels> table_{};
  std::array<glm::dvec4, kTransferEntries> rgba_{};  // the table as the compositing reads it
  std::array<double, 3> brightest_{};
  glm::dvec4 at(double x) const;  // interpolated at table position x in [0, entries - 1]
};

// One tile's bounds and plans; one per thread, kept from tile to tile.
class TilePlanner {
 public:
  // Begins a tile of `tile`'s pixels whose supports reach samples [lo, hi] of `lattice`.
  void start(const PixelRect& tile, std::int64_t lo, std::int64_t hi, const ViewFrame& f,
             const VolumeLattice& lattice, double weight_floor);

  // The cells of `bundle` holding samples [first, last] stay at full rate: a rank's part's cells
  // that other ranks reach too (shared: any light and transmittance, for the cells around them),
  // or those where some ray of the bundle ends at its walls (wall: between none of the cell's
  // samples and all of them).
  enum class Hold : std::uint8_t { wall = 1, shared = 2 };  // the larger the looser
  void hold(int bundle, std::int64_t first, std::int64_t last, Hold why);

  // One support: centre c (view space), 1 / h, weight v, value q, samples [first, last], pixels.
  template <SphKernel K>
  void add(const glm::dvec3& c, double inv_h, double v, double q, std::int64_t first,
           std::int64_t last, const PixelRect& rect);

  // Every bundle's cells planned; background(x, y): pixel (x, y)'s light behind the fluid, per
  // channel (none: zeros); `part`: a rank's part of the frame (above). Counts the cells' choices.
  template <class Background>
  void plan(const VolumeOptions& o, const TransferBounds& tf, Background&& background, bool part,
            VolumeCounts& counts) {
    plans_.assign(std::size_t(bundles_) * std::size_t(cells_), CellPlan{});
    for (int b = 0; b < bundles_; ++b) {
      const PixelRect r = bundle_rect(b);
      std::array<double, 3> behind{0, 0, 0};
      if (o.background)
        for (int y = r.y0; y <= r.y1; ++y)
          for (int x = r.x0; x <= r.x1; ++x) {
            const glm::dvec3 c = background(x, y);
            for (int ch = 0; ch < 3; ++ch)
              behind[std::size_t(ch)] = std::max(behind[std::size_t(ch)], c[ch]);
          }
      plan_bundle(b, o, tf, behind, part, counts);
    }
  }

  // Whether every cell of the bundle is at full rate (the march then reads no plan for it).
  bool full_rate(int bundle) const {
    const auto first = plans_.begin() + std::ptrdiff_t(bundle) * std::ptrdiff_t(cells_);
    return std::all_of(first, first + std::ptrdiff_t(cells_),
                       [](const CellPlan& c) { return c.level == 0; });
  }

  // The tile's bundles of kBundle^2 pixels (row-major, bundles_x() to a row), and its cells per
  // bundle: `cells()` from `first_cell()`, the cell of the tile's first sample.
  int bundles() const { return bundles_; }
  int bundles_x() const { return bundles_x_; }
  std::int64_t first_cell() const { return c0_; }
  std::int64_t cells() const { return cells_; }

  int bundle_of(int p) const {  // p: the pixel's index in the tile, row-major
    const int x = p % width_, y = p / width_;
    return x / kBundle + (y / kBundle) * bundles_x_;
  }
  const CellPlan& cell(int bundle, std::int64_t i) const {  // i: a lattice sample index
    return plans_[std::size_t(bundle) * std::size_t(cells_) + std::size_t((i >> kCellShift) - c0_)];
  }
  // The first sample at or after i in one of the bundle's super-pixel cells (none: INT64_MAX).
  // Such a cell is defined at every pixel, so each ray takes it even where the march added to
  // none of its samples (the supports reaching only super-pixels are not marched).
  std::int64_t next_super_pixel(int bundle, std::int64_t i) const {
    for (std::int64_t c = std::max(i >> kCellShift, c0_); c < c0_ + cells_; ++c)
      if (plans_[std::size_t(bundle) * std::size_t(cells_) + std::size_t(c - c0_)].level ==
          kSuperPixel)
        return std::max(i, c << kCellShift);
    return std::numeric_limits<std::int64_t>::max();
  }
  // One past the last sample of the bundle's last super-pixel cell (none: INT64_MIN).
  std::int64_t super_pixels_end(int bundle) const {
    for (std::int64_t c = c0_ + cells_; c-- > c0_;)
      if (plans_[std::size_t(bundle) * std::size_t(cells_) + std::size_t(c - c0_)].level ==
          kSuperPixel)
        return (c + 1) << kCellShift;
    return std::numeric_limits<std::int64_t>::min();
  }

 private:
  struct Bounds {  // of (I, T) of one cell, light per channel
    double i_lo[3], i_hi[3], t_lo, t_hi;
  };
  PixelRect bundle_rect(int b) const;
  std::size_t sample(int b, std::int64_t i) const {
    return std::size_t(b) * std::size_t(cells_ * kCellSamples) +
           std::size_t(i - (c0_ << kCellShift));
  }
  Bounds level_bounds(int b, std::int64_t cell, int level, const TransferBounds& tf,
                      double scale_lo, double scale_hi) const;
  void plan_bundle(int b, const VolumeOptions& o, const TransferBounds& tf,
                   const std::array<double, 3>& behind, bool part, VolumeCounts& counts);

  PixelRect tile_;
  int width_ = 0, bundles_x_ = 0, bundles_ = 0, blocks_x_ = 0, blocks_ = 0;
  double floor_ = 0;  // a sample is defined where w is at least this (render/volume.h)
  std::int64_t c0_ = 0, cells_ = 0;
  const ViewFrame* frame_ = nullptr;
  // Per sample of the tile's cells: its depth, and its length per unit of ray scale.
  std::vector<double> depth_, extent_;
  // Per bundle and sample: the lowest and highest value; per proof block and sample a lower
  // bound of the weight; per sample of the bundle being planned, whether every block's is.
  std::vector<double> q_lo_, q_hi_, w_lo_;
  std::vector<std::uint8_t> proven_;
  std::vector<CellPlan> plans_;
  std::vector<std::uint8_t> held_;  // per bundle and cell: held at full rate (hold())
  // Per proof block its corner rays (view_ray of its corner pixels); per bundle its rays'
  // scales' range.
  std::vector<std::array<glm::dvec3, 4>> corners_;
  std::vector<std::array<double, 2>> scales_;
  // plan_bundle's scratch, per cell: its bounds per level (intersected with the coarser).
  std::vector<std::array<Bounds, kCellShift + 1>> cell_bounds_;
  std::vector<std::uint8_t> most_;  // per cell: 0 (full rate only) or kSuperPixel
  std::vector<double> front_;       // per cell: the transmittance in front, at most
};

// A support's lower bound of its weight at n samples of depths z over a proof block whose corner
// rays have |d|^2 = a[j], depth nearest the centre zc[j] and squared distance there m2[j], added
// to w: the sample's points of the block lie in a rectangle of the plane z = depth, the farthest
// from the centre is a corner, and the kernel falls with distance. No branch: it vectorizes.
template <SphKernel K>
__attribute__((target_clones("avx2", "default"))) void add_weight_floor(
    const double* __restrict z, std::size_t n, const double (&zc)[4], const double (&a)[4],
    const double (&m2)[4], double v, double inv_h, double* __restrict w) {
  for (std::size_t k = 0; k < n; ++k) {
    double far2 = 0;
    for (std::size_t j = 0; j < 4; ++j) {
      const double t = z[k] - zc[j];
      far2 = std::max(far2, a[j] * t * t + m2[j]);
    }
    w[k] += v * kernel_shape<K>(std::sqrt(far2) * inv_h);
  }
}

template <SphKernel K>
void TilePlanner::add(const glm::dvec3& c, double inv_h, double v, double q, std::int64_t first,
                      std::int64_t last, const PixelRect& rect) {
  const int x0 = std::max(rect.x0, tile_.x0) - tile_.x0,
            x1 = std::min(rect.x1, tile_.x1) - tile_.x0;
  const int y0 = std::max(rect.y0, tile_.y0) - tile_.y0,
            y1 = std::min(rect.y1, tile_.y1) - tile_.y0;
  for (int by = y0 / kBundle; by <= y1 / kBundle; ++by)
    for (int bx = x0 / kBundle; bx <= x1 / kBundle; ++bx) {
      const std::size_t at = sample(bx + by * bundles_x_, first);
      for (std::size_t k = at; k <= at + std::size_t(last - first); ++k) {
        q_lo_[k] = std::min(q_lo_[k], q);
        q_hi_[k] = std::max(q_hi_[k], q);
      }
    }
  const std::size_t n = std::size_t(cells_ * kCellSamples);
  const double r = kernel_support(K) / inv_h, r2 = r * r;
  for (int py = y0 / kProofBlock; py <= y1 / kProofBlock; ++py)
    for (int px = x0 / kProofBlock; px <= x1 / kProofBlock; ++px) {
      const std::size_t block = std::size_t(px + py * blocks_x_);
      // Per corner ray d: the depth nearest c and the squared distance there (chord form).
      double zc[4], a[4], m2[4];
      for (std::size_t k = 0; k < 4; ++k) {
        const glm::dvec3& d = corners_[block][k];
        a[k] = glm::dot(d, d);
        zc[k] = glm::dot(d, c) / a[k];
        const glm::dvec3 m = zc[k] * d - c;
        m2[k] = glm::dot(m, m);
      }
      // A corner ray that passes outside the support leaves every sample's farthest corner
      // outside it: the bound is 0 there (most blocks at the support's rim).
      if (std::max({m2[0], m2[1], m2[2], m2[3]}) >= r2) continue;
      const std::size_t k0 = std::size_t(first - (c0_ << kCellShift));
      add_weight_floor<K>(&depth_[k0], std::size_t(last - first + 1), zc, a, m2, v, inv_h,
                          &w_lo_[block * n + k0]);
    }
}

}  // namespace voxspan
