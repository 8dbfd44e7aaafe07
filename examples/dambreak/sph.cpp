// DamBreak: set-up, the leapfrog step, the CFL time step and diagnostics. The pair loops
// (pressure extrapolation to the walls, momentum and continuity) are in forces.cpp.
#include "sph.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

namespace dambreak {
namespace {

constexpr std::size_t kGrain = 1 << 12;

template <class F> void parallel_over(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
                    });
}

// The grid covers the tank and its walls, with cells of the kernel support.
GridShape grid_shape(const Lattice& l, int layers, double support) {
  GridShape g;
  g.cell_size = support;
  const int n[3] = {l.tank_x, l.depth, l.tank_z};
  for (int a = 0; a < 3; ++a) {
    g.origin[std::size_t(a)] = -layers * l.dx;
    g.dims[std::size_t(a)] = int(std::ceil((n[a] + 2 * layers) * l.dx / support));
  }
  return g;
}

// Reorders the perm.size() elements of `v` from `first` on by `perm` (new slot -> old index,
// both counted from `first`) through `tmp`.
template <class T>
void gather(std::vector<T>& v, std::vector<T>& tmp, const std::vector<std::uint32_t>& perm,
            std::size_t first = 0) {
  tmp.resize(perm.size());
  parallel_over(perm.size(), [&](std::size_t i) { tmp[i] = v[first + perm[i]]; });
  if (first == 0 && perm.size() == v.size()) v.swap(tmp);
  else std::copy(tmp.begin(), tmp.end(), v.begin() + std::ptrdiff_t(first));
}

// How far past a rank's slab its ghosts reach, in kernel supports: an owned particle reads the
// fluid within one support, and the wall particles within its support read the fluid within
// one support of them (Adami's extrapolation), so two; 1 % more so that float rounding in a
// pair's distance test cannot find a neighbour that the decomposition did not send.
constexpr float kGhostSupports = 2.02f;

}  // namespace

void Fluid::resize(std::size_t n) {
  for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &rho}) v->resize(n);
  id.resize(n);
}

DamBreak::DamBreak(const Config& config, Domain* domain)
    : config_(config),
      lattice_(make_lattice(config)),
      kernel_(float(config.h_over_dx * lattice_.dx)),
      domain_(domain),
      fluid_grid_(grid_shape(lattice_, config.wall_layers, 2 * config.h_over_dx * lattice_.dx)),
      ghost_grid_(fluid_grid_.shape()),
      wall_grid_(fluid_grid_.shape()) {
  const double dx = lattice_.dx;
  const double height = lattice_.column_z * dx;
  mass_ = float(config.rest_density * dx * dx * dx);
  c0_ = config.sound_speed_factor * std::sqrt(2 * config.gravity * height);
  b_ = c0_ * c0_ * config.rest_density / 7;

  Points column = column_particles(lattice_);
  fluid_.x = std::move(column.x);
  fluid_.y = std::move(column.y);
  fluid_.z = std::move(column.z);
  const std::size_t n = fluid_.size();
  fluid_.vx.assign(n, 0);
  fluid_.vy.assign(n, 0);
  fluid_.vz.assign(n, 0);
  fluid_.id.resize(n);
  fluid_.rho.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    fluid_.id[i] = std::uint32_t(i);
    // Hydrostatic start, rho from inverting Tait: no pressure wave at release.
    const double p = config.rest_density * config.gravity * (height - fluid_.z[i]);
    fluid_.rho[i] = float(config.rest_density * std::pow(1 + p / b_, 1.0 / 7));
  }

  Points wall = wall_particles(lattice_, config.wall_layers);
  std::vector<std::uint32_t> perm;
  wall_grid_.sort(wall.x.data(), wall.y.data(), wall.z.data(), wall.x.size(), perm);
  std::vector<float> tmp;
  gather(wall.x, tmp, perm);
  gather(wall.y, tmp, perm);
  gather(wall.z, tmp, perm);
  walls_.x = std::move(wall.x);
  walls_.y = std::move(wall.y);
  walls_.z = std::move(wall.z);
  walls_.p_over_rho2.assign(walls_.size(), 0);

  if (domain_) domain_->distribute(fluid_);
  owned_ = fluid_.size();
  sort_fluid();
  update_ghosts();
  compute_rates();
  dt_ = stable_dt();
}

std::array<double, 3> DamBreak::tank_extent() const {
  return {lattice_.tank_x * lattice_.dx, lattice_.depth * lattice_.dx,
          lattice_.tank_z * lattice_.dx};
}

double DamBreak::nondimensional_time() const {
  return time_ * std::sqrt(2 * config_.gravity / config_.column_width);
}

void DamBreak::sort_fluid() {
  fluid_grid_.sort(fluid_.x.data(), fluid_.y.data(), fluid_.z.data(), owned_, permutation_);
  gather_state(0, permutation_);
}

// The ghosts are rebuilt whole from their owners' state: after the drift for the forces, and
// after the last kick so that the state a step leaves holds exact copies of the owners'.
void DamBreak::update_ghosts() {
  if (!domain_) return;
  fluid_.resize(owned_);
  domain_->append_ghosts(fluid_, kGhostSupports * kernel_.support());
  const std::size_t ghosts = fluid_.size() - owned_;
  ghost_grid_.sort(fluid_.x.data() + owned_, fluid_.y.data() + owned_, fluid_.z.data() + owned_,
                   ghosts, permutation_);
  gather_state(owned_, permutation_);
}

void DamBreak::gather_state(std::size_t first, const std::vector<std::uint32_t>& perm) {
  gather(fluid_.x, scratch_.x, perm, first);
  gather(fluid_.y, scratch_.y, perm, first);
  gather(fluid_.z, scratch_.z, perm, first);
  gather(fluid_.vx, scratch_.vx, perm, first);
  gather(fluid_.vy, scratch_.vy, perm, first);
  gather(fluid_.vz, scratch_.vz, perm, first);
  gather(fluid_.rho, scratch_.rho, perm, first);
  gather(fluid_.id, scratch_.id, perm, first);
}

void DamBreak::migrate() {
  if (!domain_) return;
  fluid_.resize(owned_);
  domain_->migrate(fluid_);
  owned_ = fluid_.size();
}

void DamBreak::compute_rates() {
  compute_fluid_pressure();
  extrapolate_wall_pressure();
  compute_forces();
}

void DamBreak::kick(float half_dt) {
  Fluid& f = fluid_;
  // Tension-free liquid: a particle that separates (spray) is a drop at rest density.
  const float rho_min = config_.tension_free ? float(config_.rest_density) : 0.0f;
  parallel_over(owned_, [&](std::size_t i) {
    f.vx[i] += half_dt * f.ax[i];
    f.vy[i] += half_dt * f.ay[i];
    f.vz[i] += half_dt * f.az[i];
    f.rho[i] = std::max(f.rho[i] + half_dt * f.drho[i], rho_min);
  });
}

void DamBreak::drift(float dt) {
  Fluid& f = fluid_;
  parallel_over(owned_, [&](std::size_t i) {
    f.x[i] += dt * f.vx[i];
    f.y[i] += dt * f.vy[i];
    f.z[i] += dt * f.vz[i];
  });
}

void DamBreak::step() {
  const float dt = float(dt_), half = 0.5f * dt;
  kick(half);
  drift(dt);
  migrate();
  sort_fluid();
  update_ghosts();
  compute_rates();
  kick(half);
  update_ghosts();
  time_ += dt_;
  ++steps_;
  dt_ = stable_dt();
}

double DamBreak::stable_dt() const {
  struct Max {
    float v2 = 0, a2 = 0;
  };
  const Fluid& f = fluid_;
  Max m = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, owned_, kGrain), Max{},
      [&](const tbb::blocked_range<std::size_t>& r, Max acc) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          acc.v2 = std::max(acc.v2, f.vx[i] * f.vx[i] + f.vy[i] * f.vy[i] + f.vz[i] * f.vz[i]);
          acc.a2 = std::max(acc.a2, f.ax[i] * f.ax[i] + f.ay[i] * f.ay[i] + f.az[i] * f.az[i]);
        }
        return acc;
      },
      [](Max a, const Max& b) {
        return Max{std::max(a.v2, b.v2), std::max(a.a2, b.a2)};
      });
  if (domain_) {
    float both[2] = {m.v2, m.a2};
    domain_->max_over_ranks(both);
    m = {both[0], both[1]};
  }
  const double h = kernel_.h;
  const double acoustic = config_.cfl * h / (c0_ + std::sqrt(double(m.v2)));
  const double force = m.a2 > 0 ? 0.25 * std::sqrt(h / std::sqrt(double(m.a2))) : acoustic;
  return std::min(acoustic, force);
}

Diagnostics DamBreak::diagnostics() const {
  const Fluid& f = fluid_;
  const auto extent = tank_extent();
  const double rho0 = config_.rest_density;
  struct Acc {
    std::size_t nonfinite = 0, outside = 0;
    double front = -1e300, max_err = 0, sum_err = 0, max_v2 = 0;
  };
  tbb::combinable<Acc> acc;
  parallel_over(owned_, [&](std::size_t i) {
    Acc& a = acc.local();
    const float v[7] = {f.x[i], f.y[i], f.z[i], f.vx[i], f.vy[i], f.vz[i], f.rho[i]};
    if (!std::all_of(v, v + 7, [](float s) { return std::isfinite(s); })) {
      ++a.nonfinite;
      return;
    }
    if (f.x[i] < 0 || f.x[i] > extent[0] || f.y[i] < 0 || f.y[i] > extent[1] || f.z[i] < 0 ||
        f.z[i] > extent[2])
      ++a.outside;
    a.front = std::max(a.front, double(f.x[i]));
    const double err = std::abs(f.rho[i] - rho0) / rho0;
    a.max_err = std::max(a.max_err, err);
    a.sum_err += err;
    a.max_v2 = std::max(a.max_v2, double(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]));
  });
  Acc sum;
  acc.combine_each([&](const Acc& a) {
    sum.nonfinite += a.nonfinite;
    sum.outside += a.outside;
    sum.front = std::max(sum.front, a.front);
    sum.max_err = std::max(sum.max_err, a.max_err);
    sum.sum_err += a.sum_err;
    sum.max_v2 = std::max(sum.max_v2, a.max_v2);
  });
  Diagnostics d;
  d.fluid = owned_;
  d.nonfinite = sum.nonfinite;
  d.outside = sum.outside;
  d.front = sum.front + 0.5 * lattice_.dx;
  d.max_density_error = sum.max_err;
  d.mean_density_error = owned_ ? sum.sum_err / double(owned_) : 0;
  d.max_speed = std::sqrt(sum.max_v2);
  return d;
}

}  // namespace dambreak
