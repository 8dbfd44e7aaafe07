#include "render/cpu/volume_adaptive.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace voxspan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double width(double lo, double hi) { return std::max(hi - lo, 0.0); }

// The part of a coarse level's bound width that relax leaves ([HOK16] sec. 5.1).
double relaxed(double level_width, double full_rate_width, double relax) {
  return std::max(level_width - relax * full_rate_width, 0.0);
}

}  // namespace

TransferBounds::TransferBounds(const VolumeOptions& o)
    : log_(o.transfer.log),
      lo_(double(o.transfer.place().lo)),
      scale_(double(o.transfer.place().scale)),
      inv_length_(1 / double(float(o.opacity_length))) {
  for (std::size_t k = 0; k < rgba_.size(); ++k) {
    rgba_[k] = glm::dvec4(o.transfer.rgba[k]);
    for (std::size_t ch = 0; ch < 4; ++ch)
      table_[0][k][ch] = table_[0][k][ch + 4] = rgba_[k][int(ch)];
    for (std::size_t ch = 0; ch < 3; ++ch)
      brightest_[ch] = std::max(brightest_[ch], rgba_[k][int(ch)]);
  }
  for (std::size_t j = 1; j < std::size_t(kLevels); ++j)
    for (std::size_t k = 0; k + (std::size_t(1) << j) <= rgba_.size(); ++k) {
      const auto& a = table_[j - 1][k];
      const auto& b = table_[j - 1][k + (std::size_t(1) << (j - 1))];
      for (std::size_t ch = 0; ch < 4; ++ch) {
        table_[j][k][ch] = std::min(a[ch], b[ch]);
        table_[j][k][ch + 4] = std::max(a[ch + 4], b[ch + 4]);
      }
    }
}

glm::dvec4 TransferBounds::at(double x) const {
  const int k = std::min(int(x), kTransferEntries - 2);
  const double f = x - double(k);
  return rgba_[std::size_t(k)] * (1 - f) + rgba_[std::size_t(k + 1)] * f;
}

TransferBounds::Range TransferBounds::over(double q_lo, double q_hi) const {
  // The compositing finds the table position in float (on a log scale from float's log2 of a
  // value rounded to float, 1e-7 off in log2): widened by its rounding. The log is monotone, so
  // the bounds of the values bound their positions.
  const auto position = [&](double q) { return !log_ ? q : q > 0 ? std::log2(q) : lo_ - 1; };
  const double va = position(q_lo), vb = position(q_hi);
  const double top = kTransferEntries - 1;
  const double pad =
      1e-4 + 2e-7 * (std::abs(va) + std::abs(vb) + 2 * std::abs(lo_) + (log_ ? 2 : 0)) * scale_;
  const double xa = std::clamp((va - lo_) * scale_ - pad, 0.0, top);
  const double xb = std::clamp((vb - lo_) * scale_ + pad, 0.0, top);
  const glm::dvec4 ea = at(xa), eb = at(xb);
  double lo[4], hi[4];
  for (int ch = 0; ch < 4; ++ch)
    lo[ch] = std::min(ea[ch], eb[ch]), hi[ch] = std::max(ea[ch], eb[ch]);
  // The entries strictly inside: a sparse-table range query.
  const int k0 = int(std::floor(xa)) + 1, k1 = int(std::ceil(xb)) - 1;
  if (k0 <= k1) {
    const int j = std::bit_width(unsigned(k1 - k0 + 1)) - 1;
    const auto& a = table_[std::size_t(j)][std::size_t(k0)];
    const auto& b = table_[std::size_t(j)][std::size_t(k1 - (1 << j) + 1)];
    for (std::size_t ch = 0; ch < 4; ++ch) {
      lo[ch] = std::min({lo[ch], a[ch], b[ch]});
      hi[ch] = std::max({hi[ch], a[ch + 4], b[ch + 4]});
    }
  }
  return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, lo[3], hi[3]};
}

double TransferBounds::opacity(double alpha, double length) const {
  if (alpha >= 1) return 1;
  if (alpha <= 0) return 0;
  return 1 - std::exp2(std::log2(1 - alpha) * (length * inv_length_));
}

void TilePlanner::start(const PixelRect& tile, std::int64_t lo, std::int64_t hi, const ViewFrame& f,
                        const VolumeLattice& lattice, double weight_floor) {
  // With room for the sums' rounding; w > 0 is needed too.
  floor_ = std::max(weight_floor * (1 + 1e-9), 1e-300);
  tile_ = tile;
  frame_ = &f;
  width_ = tile.x1 - tile.x0 + 1;
  bundles_x_ = (width_ + kBundle - 1) / kBundle;
  bundles_ = bundles_x_ * ((tile.y1 - tile.y0 + kBundle) / kBundle);
  blocks_x_ = (width_ + kProofBlock - 1) / kProofBlock;
  blocks_ = blocks_x_ * ((tile.y1 - tile.y0 + kProofBlock) / kProofBlock);
  c0_ = lo >> kCellShift;
  cells_ = (hi >> kCellShift) - c0_ + 1;
  const std::size_t n = std::size_t(cells_ * kCellSamples);
  depth_.resize(n);
  extent_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    depth_[k] = lattice.depth((c0_ << kCellShift) + std::int64_t(k));
    extent_[k] = lattice.extent(depth_[k]);
  }
  held_.assign(std::size_t(bundles_) * std::size_t(cells_), 0);
  q_lo_.assign(n * std::size_t(bundles_), kInf);
  q_hi_.assign(q_lo_.size(), -kInf);
  w_lo_.assign(n * std::size_t(blocks_), 0.0);
  corners_.resize(std::size_t(blocks_));
  for (int k = 0; k < blocks_; ++k) {
    const int x0 = tile.x0 + (k % blocks_x_) * kProofBlock;
    const int y0 = tile.y0 + (k / blocks_x_) * kProofBlock;
    const int x1 = std::min(x0 + kProofBlock - 1, tile.x1),
              y1 = std::min(y0 + kProofBlock - 1, tile.y1);
    corners_[std::size_t(k)] = {f.view_ray(x0, y0), f.view_ray(x1, y0), f.view_ray(x0, y1),
                                f.view_ray(x1, y1)};
  }
  scales_.resize(std::size_t(bundles_));
  for (int b = 0; b < bundles_; ++b) {
    const PixelRect r = bundle_rect(b);
    // As the march finds each ray's scale (in float).
    double s_lo = kInf, s_hi = 0;
    for (int y = r.y0; y <= r.y1; ++y)
      for (int x = r.x0; x <= r.x1; ++x) {
        const double s = double(float(glm::length(f.view_ray(x, y))));
        s_lo = std::min(s_lo, s);
        s_hi = std::max(s_hi, s);
      }
    scales_[std::size_t(b)] = {s_lo, s_hi};
  }
}

void TilePlanner::hold(int bundle, std::int64_t first, std::int64_t last, Hold why) {
  const std::int64_t c_first = std::max(first >> kCellShift, c0_);
  const std::int64_t c_last = std::min(last >> kCellShift, c0_ + cells_ - 1);
  for (std::int64_t c = c_first; c <= c_last; ++c) {
    std::uint8_t& h = held_[std::size_t(bundle) * std::size_t(cells_) + std::size_t(c - c0_)];
    h = std::max(h, std::uint8_t(why));
  }
}

PixelRect TilePlanner::bundle_rect(int b) const {
  const int x0 = tile_.x0 + (b % bundles_x_) * kBundle, y0 = tile_.y0 + (b / bundles_x_) * kBundle;
  return {x0, y0, std::min(x0 + kBundle - 1, tile_.x1), std::min(y0 + kBundle - 1, tile_.y1)};
}

TilePlanner::Bounds TilePlanner::level_bounds(int b, std::int64_t cell, int level,
                                              const TransferBounds& tf, double scale_lo,
                                              double scale_hi) const {
  Bounds r{{0, 0, 0}, {0, 0, 0}, 1, 1};
  const int step = 1 << level;
  for (int j0 = 0; j0 < kCellSamples; j0 += step) {
    double q_lo = kInf, q_hi = -kInf, length = 0;
    bool may_be_empty = false;
    for (int j = j0; j < j0 + step; ++j) {
      const std::int64_t i = (cell << kCellShift) + j;
      const std::size_t k = sample(b, i);
      q_lo = std::min(q_lo, q_lo_[k]);
      q_hi = std::max(q_hi, q_hi_[k]);
      may_be_empty = may_be_empty || proven_[std::size_t(i - (c0_ << kCellShift))] == 0;
      length += extent_[std::size_t(i - (c0_ << kCellShift))];
    }
    if (q_lo > q_hi) continue;  // no support reaches the run: empty at every pixel, exactly
    const TransferBounds::Range t = tf.over(q_lo, q_hi);
    const double a_lo = tf.opacity(t.alpha_lo, length * scale_lo);
    const double a_hi = tf.opacity(t.alpha_hi, length * scale_hi);
    for (int ch = 0; ch < 3; ++ch) {
      r.i_lo[ch] += (may_be_empty ? 0.0 : t.c_lo[ch] * a_lo) * r.t_lo;
      r.i_hi[ch] += t.c_hi[ch] * a_hi * r.t_hi;
    }
    r.t_lo *= 1 - a_hi;
    r.t_hi *= may_be_empty ? 1.0 : 1 - a_lo;
  }
  return r;
}

void TilePlanner::plan_bundle(int b, const VolumeOptions& o, const TransferBounds& tf,
                              const std::array<double, 3>& behind, bool part,
                              VolumeCounts& counts) {
  const std::size_t n = std::size_t(cells_);
  cell_bounds_.resize(n);
  most_.resize(n);
  const auto [scale_lo, scale_hi] = scales_[std::size_t(b)];
  // A sample is defined at every pixel of the bundle where every proof block's bound is.
  const std::size_t samples = n * std::size_t(kCellSamples);
  proven_.assign(samples, 1);
  const PixelRect r = bundle_rect(b);
  for (int py = (r.y0 - tile_.y0) / kProofBlock; py <= (r.y1 - tile_.y0) / kProofBlock; ++py)
    for (int px = (r.x0 - tile_.x0) / kProofBlock; px <= (r.x1 - tile_.x0) / kProofBlock; ++px) {
      const double* w = &w_lo_[std::size_t(px + py * blocks_x_) * samples];
      for (std::size_t k = 0; k < samples; ++k) proven_[k] = proven_[k] && w[k] >= floor_;
    }
  for (std::size_t c = 0; c < n; ++c) {
    const std::int64_t cell = c0_ + std::int64_t(c);
    bool reached = false, proven = true;
    for (int j = 0; j < kCellSamples; ++j) {
      const std::size_t k = sample(b, (cell << kCellShift) + j);
      reached = reached || q_lo_[k] <= q_hi_[k];
      proven = proven && proven_[std::size_t(((cell - c0_) << kCellShift) + j)] != 0;
    }
    auto& bounds = cell_bounds_[c];
    const std::uint8_t held = held_[std::size_t(b) * n + c];
    if (held == std::uint8_t(Hold::wall) && reached) {  // a ray ends inside: part of the cell
      most_[c] = 0;
      const Bounds full = level_bounds(b, cell, 0, tf, scale_lo, scale_hi);
      bounds.fill(Bounds{{0, 0, 0}, {full.i_hi[0], full.i_hi[1], full.i_hi[2]}, full.t_lo, 1});
      continue;
    }
    if (held == std::uint8_t(Hold::shared)) {  // another rank's sums there: any value
      most_[c] = 0;
      bounds.fill(Bounds{{0, 0, 0}, {tf.brightest(0), tf.brightest(1), tf.brightest(2)}, 0, 1});
      continue;
    }
    const bool surface = !proven && o.adaptive.rules.surface_rule;
    most_[c] = reached && !surface ? kSuperPixel : 0;
    if (!reached) {
      bounds.fill(Bounds{{0, 0, 0}, {0, 0, 0}, 1, 1});
      continue;
    }
    if (surface) {  // the free surface: full rate ([HOK16] sec. 4.2)
      ++counts.cells_surface;
      bounds.fill(level_bounds(b, cell, 0, tf, scale_lo, scale_hi));
      continue;
    }
    for (int l = 0; l <= kCellShift; ++l)
      bounds[std::size_t(l)] = level_bounds(b, cell, l, tf, scale_lo, scale_hi);
    // Every level's bounds hold the full-rate cell and level l's those of levels up to l: keep
    // the intersections (level l: of levels l and coarser).
    for (int l = kCellShift - 1; l >= 0; --l) {
      Bounds& x = bounds[std::size_t(l)];
      const Bounds& y = bounds[std::size_t(l + 1)];
      for (int ch = 0; ch < 3; ++ch)
        x.i_lo[ch] = std::max(x.i_lo[ch], y.i_lo[ch]),
        x.i_hi[ch] = std::min(x.i_hi[ch], y.i_hi[ch]);
      x.t_lo = std::max(x.t_lo, y.t_lo);
      x.t_hi = std::min(x.t_hi, y.t_hi);
    }
  }
  // The widest transmittance a cell may take, whatever is chosen for it.
  const auto loosest = [&](std::size_t c) -> const Bounds& {
    return cell_bounds_[c][most_[c] == 0 ? 0 : std::size_t(kCellShift)];
  };
  double t_end_lo = 1;
  for (std::size_t c = 0; c < n; ++c) t_end_lo *= loosest(c).t_lo;
  // A part's ray may stop at another rank's sample.
  const bool may_stop = o.termination > 0 && (part || t_end_lo < o.termination);
  const double tol = o.adaptive.error_tolerance - kRoundingReserve;
  const double share = o.adaptive.share;
  std::array<double, 3> brightest{};  // M per channel
  for (int ch = 0; ch < 3; ++ch)
    brightest[std::size_t(ch)] = std::max(tf.brightest(ch), behind[std::size_t(ch)]);
  std::array<double, 4> budget{};  // per channel, alpha last (no background: 1 - T)
  for (int ch = 0; ch < 3; ++ch)
    budget[std::size_t(ch)] =
        share * (tol - (may_stop ? 2 * o.termination * brightest[std::size_t(ch)] : 0));
  budget[3] = o.background ? kInf : share * (tol - (may_stop ? 2 * o.termination : 0));
  if (std::min({budget[0], budget[1], budget[2], budget[3]}) <= 0) return;

  // Back to front ([HOK16] sec. 4.4). The light behind a cell bounded as the full-rate picture
  // has it; the transmittance in front with any choice of the cells there.
  front_.resize(n);
  double front = 1;  // forward: a product of many opaque cells underflows, and stays 0
  for (std::size_t c = 0; c < n; ++c) {
    front_[c] = front;
    front *= loosest(c).t_hi;
  }
  std::array<double, 3> back = part ? brightest : behind;
  std::array<double, 4> spent{};
  const AdaptiveOptions::Rules& rules = o.adaptive.rules;
  std::array<std::uint8_t, kCellShift + 1> choices{};  // the cheapest first
  std::size_t n_choices = 0;
  if (rules.super_pixels) choices[n_choices++] = kSuperPixel;
  for (std::uint8_t l = kCellShift; rules.coarse && l >= 1; --l) choices[n_choices++] = l;
  for (std::size_t c = n; c-- > 0;) {
    const Bounds& full = cell_bounds_[c][0];
    const double front_hi = front_[c];
    if (most_[c] != 0) {
      for (std::size_t k = 0; k < n_choices; ++k) {
        const std::uint8_t choice = choices[k];
        std::array<double, 4> term{};
        if (choice == kSuperPixel) {  // the middle of the full-rate bounds: half their width
          for (int ch = 0; ch < 3; ++ch)
            term[std::size_t(ch)] = 0.5 * (width(full.i_lo[ch], full.i_hi[ch]) +
                                           width(full.t_lo, full.t_hi) * back[std::size_t(ch)]);
          term[3] = 0.5 * width(full.t_lo, full.t_hi);
        } else {
          const Bounds& x = cell_bounds_[c][choice];
          const double relax = o.adaptive.relax;
          const double wt = relaxed(width(x.t_lo, x.t_hi), width(full.t_lo, full.t_hi), relax);
          for (int ch = 0; ch < 3; ++ch)
            term[std::size_t(ch)] =
                relaxed(width(x.i_lo[ch], x.i_hi[ch]), width(full.i_lo[ch], full.i_hi[ch]), relax) +
                wt * back[std::size_t(ch)];
          term[3] = wt;
        }
        bool fits = true;  // without the greedy step: the cell's own term alone
        for (std::size_t ch = 0; ch < 4; ++ch)
          fits = fits && (rules.greedy ? spent[ch] : 0) + front_hi * term[ch] <= budget[ch];
        if (!fits) continue;
        for (std::size_t ch = 0; ch < 4; ++ch) spent[ch] += front_hi * term[ch];
        CellPlan& plan = plans_[std::size_t(b) * n + c];
        plan.level = choice;
        if (choice == kSuperPixel) {
          for (int ch = 0; ch < 3; ++ch)
            plan.light[ch] = float(0.5 * (full.i_lo[ch] + full.i_hi[ch]));
          plan.transmittance = float(0.5 * (full.t_lo + full.t_hi));
          ++counts.cells_super_pixel;
        } else {
          ++counts.cells_coarse;
        }
        break;
      }
    }
    if (!part)
      for (int ch = 0; ch < 3; ++ch)
        back[std::size_t(ch)] = full.i_hi[ch] + full.t_hi * back[std::size_t(ch)];
  }
  // The picture's alpha moves by the transmittance's change (no background), else not at all.
  const double spent_alpha = o.background ? 0 : spent[3];
  counts.error_bound = std::max({counts.error_bound, spent[0], spent[1], spent[2], spent_alpha});
}

}  // namespace voxspan
