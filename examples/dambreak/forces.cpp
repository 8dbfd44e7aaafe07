// The pair loops of the WCSPH step, parallel over the cells of the neighbour grid: each
// fluid cell gathers from the 9 particle ranges covering its 27 neighbour cells, in the fluid
// and in the wall grid (and in the ghost grid of a distributed run: 9 ranges more). Gather
// form (no writes to neighbours), so no atomics.
//   * fluid pressure: Tait, p = B ((rho/rho0)^7 - 1), clamped at 0 (Config::tension_free),
//     stored as p / rho^2;
//   * wall pressure (Adami, Hu & Adams 2012, eq. 27): p_w = (sum_f p_f W_wf + g . sum_f rho_f
//     (x_w - x_f) W_wf) / sum_f W_wf, clamped at 0 so walls never pull fluid; rho_w from Tait;
//   * momentum: dv_i/dt = -sum_j m (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) grad W_ij + g, with
//     Pi_ij = -alpha c0 mu_ij / rho_ij, mu_ij = h v_ij.x_ij / (r^2 + 0.01 h^2) when v_ij.x_ij < 0;
//   * continuity: drho_i/dt = sum_j m v_ij . grad W_ij + delta h c0 sum_j psi_ij . grad W_ij
//   m/rho_j
//     with psi_ij = 2 (rho_j - rho_i) x_ji / r^2 (fluid pairs only; psi . grad W = -2 (rho_j -
//     rho_i) fw, the regularisation of r^2 is left out).
// Costs: per fluid particle ~27 cells x (2h)^3/dx^3/27 candidates, about 60 neighbours at
// h = 1.2 dx; per wall particle next to the fluid the same over fluid candidates.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "sph.h"

namespace dambreak {

float DamBreak::pressure_of(float rho) const {
  const float s = rho * float(1 / config_.rest_density), s2 = s * s, s4 = s2 * s2;
  const float p_min = config_.tension_free ? 0.0f : -std::numeric_limits<float>::max();
  return std::max(p_min, float(b_) * (s4 * s2 * s - 1));
}

void DamBreak::compute_fluid_pressure() {
  Fluid& f = fluid_;
  f.p_over_rho2.resize(f.size());
  f.volume.resize(f.size());
  const float m = mass_;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 1 << 12),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        f.p_over_rho2[i] = pressure_of(f.rho[i]) / (f.rho[i] * f.rho[i]);
                        f.volume[i] = m / f.rho[i];
                      }
                    });
}

void DamBreak::pressure(std::vector<float>& out) const {
  out.resize(fluid_.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 1 << 12),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        out[i] = pressure_of(fluid_.rho[i]);
                    });
}

namespace {

struct ForceTerms {
  CubicSpline kernel;
  float support2, eta2, m, alpha_c0_h, delta_h_c0, rho0, g;
  bool wall_viscosity;
};

// The neighbour candidates of one cell, copied into contiguous SoA buffers: the pair loops
// then run over one long array (good SIMD trip counts) instead of 9 short ranges, and
// candidates farther than the support from the cell's particles are dropped up front.
struct Candidates {
  std::vector<float> x, y, z, vx, vy, vz, rho, p_over_rho2, volume;
  std::size_t n = 0;

  void reserve(std::size_t count) {
    for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &rho, &p_over_rho2, &volume})
      if (v->size() < count) v->resize(count);
    n = 0;
  }
};

struct Box {
  float lo[3], hi[3];
  float distance2(float px, float py, float pz) const {
    const float p[3] = {px, py, pz};
    float d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const float d = p[a] < lo[a] ? lo[a] - p[a] : p[a] > hi[a] ? p[a] - hi[a] : 0.0f;
      d2 += d * d;
    }
    return d2;
  }
};

// The bounding box of the particles of one cell (x, y, z of the fluid or of the walls).
Box bounds(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z,
           Range own) {
  Box b{{x[own.begin], y[own.begin], z[own.begin]}, {x[own.begin], y[own.begin], z[own.begin]}};
  for (std::uint32_t i = own.begin + 1; i < own.end; ++i) {
    const float p[3] = {x[i], y[i], z[i]};
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], p[a]);
      b.hi[a] = std::max(b.hi[a], p[a]);
    }
  }
  return b;
}

std::size_t total(std::span<const Range> ranges) {
  std::size_t n = 0;
  for (const Range& r : ranges) n += r.end - r.begin;
  return n;
}

void gather_fluid(const Fluid& f, std::span<const Range> ranges, const Box& box, float support2,
                  Candidates& c) {
  c.reserve(total(ranges));
  for (const Range& r : ranges)
    for (std::uint32_t j = r.begin; j < r.end; ++j) {
      if (box.distance2(f.x[j], f.y[j], f.z[j]) >= support2) continue;
      const std::size_t q = c.n++;
      c.x[q] = f.x[j], c.y[q] = f.y[j], c.z[q] = f.z[j];
      c.vx[q] = f.vx[j], c.vy[q] = f.vy[j], c.vz[q] = f.vz[j];
      c.rho[q] = f.rho[j], c.p_over_rho2[q] = f.p_over_rho2[j], c.volume[q] = f.volume[j];
    }
}

void gather_walls(const Walls& w, std::span<const Range> ranges, const Box& box, float support2,
                  Candidates& c) {
  c.reserve(total(ranges));
  for (const Range& r : ranges)
    for (std::uint32_t j = r.begin; j < r.end; ++j) {
      if (box.distance2(w.x[j], w.y[j], w.z[j]) >= support2) continue;
      const std::size_t q = c.n++;
      c.x[q] = w.x[j], c.y[q] = w.y[j], c.z[q] = w.z[j], c.p_over_rho2[q] = w.p_over_rho2[j];
    }
}

// The rates of the particles of one cell. Built for AVX2 too (8 lanes) and picked at run
// time where the CPU has it. The particle itself and candidates beyond the support add
// exactly 0 (x_ij = v_ij = 0, or fw = 0), so the loops have no branches.
__attribute__((target_clones("avx2", "default"))) void cell_rates(const ForceTerms& t, Fluid& f,
                                                                  Range own, const Candidates& fc,
                                                                  const Candidates& wc) {
  const CubicSpline kernel = t.kernel;  // a local copy: its fields stay in registers
  const float support2 = t.support2, eta2 = t.eta2, m = t.m, alpha_c0_h = t.alpha_c0_h;
  const float rho0 = t.rho0;
  const bool wall_viscosity = t.wall_viscosity;
  const float* __restrict cx = fc.x.data();
  const float* __restrict cy = fc.y.data();
  const float* __restrict cz = fc.z.data();
  const float* __restrict cvx = fc.vx.data();
  const float* __restrict cvy = fc.vy.data();
  const float* __restrict cvz = fc.vz.data();
  const float* __restrict crho = fc.rho.data();
  const float* __restrict cp = fc.p_over_rho2.data();
  const float* __restrict cvol = fc.volume.data();
  for (std::uint32_t i = own.begin; i < own.end; ++i) {
    const float xi = f.x[i], yi = f.y[i], zi = f.z[i];
    const float vxi = f.vx[i], vyi = f.vy[i], vzi = f.vz[i], rhoi = f.rho[i];
    const float pi = f.p_over_rho2[i];
    float ax = 0, ay = 0, az = 0, drho = 0, diffusion = 0;
#pragma omp simd reduction(+ : ax, ay, az, drho, diffusion)
    for (std::size_t j = 0; j < fc.n; ++j) {
      const float dx = xi - cx[j], dy = yi - cy[j], dz = zi - cz[j];
      const float r2 = dx * dx + dy * dy + dz * dz;
      const float fw = r2 < support2 ? kernel.dw_over_r(std::sqrt(r2)) : 0.0f;
      const float dvx = vxi - cvx[j], dvy = vyi - cvy[j], dvz = vzi - cvz[j];
      const float vr = dvx * dx + dvy * dy + dvz * dz;
      const float viscous =
          vr < 0 ? alpha_c0_h * vr / ((r2 + eta2) * 0.5f * (rhoi + crho[j])) : 0.0f;
      const float s = -m * (pi + cp[j] - viscous) * fw;
      ax += s * dx;
      ay += s * dy;
      az += s * dz;
      drho += m * vr * fw;
      diffusion += -2 * (crho[j] - rhoi) * fw * cvol[j];
    }
    const float* __restrict wx = wc.x.data();
    const float* __restrict wy = wc.y.data();
    const float* __restrict wz = wc.z.data();
    const float* __restrict wp = wc.p_over_rho2.data();
#pragma omp simd reduction(+ : ax, ay, az, drho)
    for (std::size_t j = 0; j < wc.n; ++j) {
      const float dx = xi - wx[j], dy = yi - wy[j], dz = zi - wz[j];
      const float r2 = dx * dx + dy * dy + dz * dz;
      const float fw = r2 < support2 ? kernel.dw_over_r(std::sqrt(r2)) : 0.0f;
      const float vr = vxi * dx + vyi * dy + vzi * dz;  // walls are at rest
      const float viscous =
          wall_viscosity && vr < 0 ? alpha_c0_h * vr / ((r2 + eta2) * rho0) : 0.0f;
      const float s = -m * (pi + wp[j] - viscous) * fw;
      ax += s * dx;
      ay += s * dy;
      az += s * dz;
      drho += m * vr * fw;
    }
    f.ax[i] = ax;
    f.ay[i] = ay;
    f.az[i] = az - t.g;
    f.drho[i] = drho + t.delta_h_c0 * diffusion;
  }
}

// Adami et al. (2012) eq. 27 for the wall particles of one cell, from the fluid candidates.
__attribute__((target_clones("avx2", "default"))) void cell_wall_pressure(
    const CubicSpline& kernel_ref, float support2, float g, float rho0, float b, Walls& w,
    Range own, const Candidates& fc) {
  const CubicSpline kernel = kernel_ref;
  const float* __restrict cx = fc.x.data();
  const float* __restrict cy = fc.y.data();
  const float* __restrict cz = fc.z.data();
  const float* __restrict crho = fc.rho.data();
  const float* __restrict cp = fc.p_over_rho2.data();
  for (std::uint32_t i = own.begin; i < own.end; ++i) {
    const float xi = w.x[i], yi = w.y[i], zi = w.z[i];
    float sum_w = 0, sum_pw = 0, sum_hydro = 0;
#pragma omp simd reduction(+ : sum_w, sum_pw, sum_hydro)
    for (std::size_t j = 0; j < fc.n; ++j) {
      const float dx = xi - cx[j], dy = yi - cy[j], dz = zi - cz[j];
      const float r2 = dx * dx + dy * dy + dz * dz;
      const float wk = r2 < support2 ? kernel.w(std::sqrt(r2)) : 0.0f;
      sum_w += wk;
      sum_pw += cp[j] * crho[j] * crho[j] * wk;
      sum_hydro += crho[j] * (-g * dz) * wk;  // g . (x_w - x_f), gravity along -z
    }
    const float p = sum_w > 0 ? std::max((sum_pw + sum_hydro) / sum_w, 0.0f) : 0.0f;
    const float rho = rho0 * std::pow(1 + p / b, 1.0f / 7);
    w.p_over_rho2[i] = p / (rho * rho);
  }
}

}  // namespace

int DamBreak::fluid_ranges(std::size_t cell, std::array<Range, 18>& out) const {
  std::array<Range, 9> own, ghosts;
  const int n = fluid_grid_.neighbour_ranges(cell, own);
  const int g = fluid_.size() > owned_ ? ghost_grid_.neighbour_ranges(cell, ghosts) : 0;
  std::copy_n(own.begin(), n, out.begin());
  const auto base = std::uint32_t(owned_);
  for (int k = 0; k < g; ++k)
    out[std::size_t(n + k)] = {ghosts[std::size_t(k)].begin + base,
                               ghosts[std::size_t(k)].end + base};
  return n + g;
}

void DamBreak::extrapolate_wall_pressure() {
  const float support2 = kernel_.support() * kernel_.support();
  const float g = float(config_.gravity), rho0 = float(config_.rest_density), b = float(b_);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, wall_grid_.shape().cell_count(), 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::array<Range, 18> ranges;
                      Candidates fluid;
                      for (std::size_t c = r.begin(); c != r.end(); ++c) {
                        const Range own = wall_grid_.cell(c);
                        if (own.begin == own.end) continue;
                        const std::span<const Range> near(ranges.data(),
                                                          std::size_t(fluid_ranges(c, ranges)));
                        // No fluid near: p = 0, as the sums would give, without Tait's pow per
                        // particle (most walls, and in a distributed run all but the walls near
                        // this rank's fluid).
                        if (total(near) == 0) {
                          std::fill(walls_.p_over_rho2.begin() + own.begin,
                                    walls_.p_over_rho2.begin() + own.end, 0.0f);
                          continue;
                        }
                        const Box box = bounds(walls_.x, walls_.y, walls_.z, own);
                        gather_fluid(fluid_, near, box, support2, fluid);
                        cell_wall_pressure(kernel_, support2, g, rho0, b, walls_, own, fluid);
                      }
                    });
}

void DamBreak::compute_forces() {
  Fluid& f = fluid_;
  const std::size_t n = owned_;
  f.ax.resize(n);
  f.ay.resize(n);
  f.az.resize(n);
  f.drho.resize(n);
  const float h = kernel_.h, c0 = float(c0_);
  const ForceTerms terms{kernel_,
                         kernel_.support() * kernel_.support(),
                         0.01f * h * h,
                         mass_,
                         float(config_.alpha) * c0 * h,
                         float(config_.delta) * h * c0,
                         float(config_.rest_density),
                         float(config_.gravity),
                         config_.wall_viscosity};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fluid_grid_.shape().cell_count(), 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::array<Range, 18> ranges;
                      std::array<Range, 9> wall_ranges;
                      Candidates fluid, walls;
                      for (std::size_t c = r.begin(); c != r.end(); ++c) {
                        const Range own = fluid_grid_.cell(c);
                        if (own.begin == own.end) continue;
                        const Box box = bounds(f.x, f.y, f.z, own);
                        gather_fluid(f, {ranges.data(), std::size_t(fluid_ranges(c, ranges))}, box,
                                     terms.support2, fluid);
                        gather_walls(walls_,
                                     {wall_ranges.data(),
                                      std::size_t(wall_grid_.neighbour_ranges(c, wall_ranges))},
                                     box, terms.support2, walls);
                        cell_rates(terms, f, own, fluid, walls);
                      }
                    });
}

}  // namespace dambreak
