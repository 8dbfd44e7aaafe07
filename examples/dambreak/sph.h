// sph.h - a weakly compressible SPH solver (WCSPH) for the dam break:
//   * Tait equation of state p = B ((rho / rho0)^7 - 1), B = c0^2 rho0 / 7 (Monaghan 1994);
//     the liquid sustains no tension: p >= 0 and rho >= rho0 (Config::tension_free);
//   * density by the continuity equation with delta-SPH diffusion (Molteni & Colagrossi 2009);
//   * momentum with the symmetric pressure term and Monaghan's artificial viscosity, against
//     the walls too (their friction; Config::wall_viscosity);
//   * cubic-spline kernel (kernel.h), h = 1.2 dx;
//   * walls of three layers of fixed particles whose pressure is extrapolated from the fluid
//     with the hydrostatic correction of Adami, Hu & Adams (2012);
//   * kick-drift-kick leapfrog, CFL time step on c0 + max |v| and on max |a|;
//   * a cell-sorted neighbour grid (neighbour_grid.h), particles re-sorted every step,
//     loops parallel over cells with oneTBB.
// The fluid arrays are SoA floats in cell order; fluid_grid().offsets() is the compact grid.
#pragma once

#include <cstdint>
#include <vector>

#include "kernel.h"
#include "neighbour_grid.h"
#include "scene.h"

namespace dambreak {

struct Fluid {
  std::vector<float> x, y, z, vx, vy, vz, rho;  // state, in cell order
  std::vector<float> ax, ay, az, drho;          // rates from the latest force evaluation
  std::vector<float> p_over_rho2;               // p / rho^2 of the latest evaluation
  std::vector<float> volume;                    // m / rho of the latest evaluation
  std::vector<std::uint32_t> id;                // the particle's index at t = 0
  std::size_t size() const { return x.size(); }
};

struct Walls {
  std::vector<float> x, y, z;
  std::vector<float> p_over_rho2;  // extrapolated each step (Adami et al. 2012)
  std::size_t size() const { return x.size(); }
};

struct Diagnostics {
  std::size_t nonfinite = 0;     // particles with a NaN/inf position, velocity or density
  std::size_t outside = 0;       // fluid particle centres outside the tank interior
  double front = 0;              // leading edge: max x + dx / 2
  double max_density_error = 0;  // max |rho - rho0| / rho0
  double mean_density_error = 0;
  double max_speed = 0;
};

class DamBreak {
 public:
  explicit DamBreak(const Config& config);

  // One time step of the size chosen after the previous one.
  void step();

  double time() const { return time_; }
  // Martin & Moyce's T = t sqrt(2 g / a).
  double nondimensional_time() const;
  std::int64_t steps() const { return steps_; }
  double dt() const { return dt_; }

  const Config& config() const { return config_; }
  const Lattice& lattice() const { return lattice_; }
  double dx() const { return lattice_.dx; }
  double smoothing_length() const { return kernel_.h; }
  double sound_speed() const { return c0_; }
  float particle_mass() const { return mass_; }
  // Tank interior: [0, extent[0]] x [0, extent[1]] x [0, extent[2]].
  std::array<double, 3> tank_extent() const;

  const Fluid& fluid() const { return fluid_; }
  const Walls& walls() const { return walls_; }
  const NeighbourGrid& fluid_grid() const { return fluid_grid_; }

  Diagnostics diagnostics() const;

 private:
  void sort_fluid();
  void compute_fluid_pressure();
  void extrapolate_wall_pressure();
  void compute_rates();
  void compute_forces();
  void kick(float half_dt);
  double stable_dt() const;

  Config config_;
  Lattice lattice_;
  CubicSpline kernel_;
  float mass_ = 0;
  double c0_ = 0, b_ = 0;
  Fluid fluid_, scratch_;
  Walls walls_;
  NeighbourGrid fluid_grid_, wall_grid_;
  std::vector<std::uint32_t> permutation_;
  double time_ = 0, dt_ = 0;
  std::int64_t steps_ = 0;
};

}  // namespace dambreak
