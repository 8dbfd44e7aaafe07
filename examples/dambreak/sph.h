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
// With a Domain (below) the solver is one rank of a distributed run: the same step on the
// particles it owns, with ghosts from the other ranks as extra neighbours.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "kernel.h"
#include "neighbour_grid.h"
#include "scene.h"

namespace dambreak {

// In a distributed run the arrays hold the owned particles first, in cell order, then the
// ghosts, in cell order too; the rates only the owned particles'.
struct Fluid {
  std::vector<float> x, y, z, vx, vy, vz, rho;  // state, in cell order
  std::vector<float> ax, ay, az, drho;          // rates from the latest force evaluation
  std::vector<float> p_over_rho2;               // p / rho^2 of the latest evaluation
  std::vector<float> volume;                    // m / rho of the latest evaluation
  std::vector<std::uint32_t> id;                // the particle's index at t = 0
  std::size_t size() const { return x.size(); }
  // Resizes the state (positions, velocities, densities, ids): what a particle carries from
  // step to step, and all that migration and ghosts copy. The rest is recomputed each step.
  void resize(std::size_t n);
};

struct Walls {
  std::vector<float> x, y, z;
  std::vector<float> p_over_rho2;  // extrapolated each step (Adami et al. 2012)
  std::size_t size() const { return x.size(); }
};

struct Diagnostics {
  std::size_t fluid = 0;         // fluid particles (owned ones, in a distributed run)
  std::size_t nonfinite = 0;     // particles with a NaN/inf position, velocity or density
  std::size_t outside = 0;       // fluid particle centres outside the tank interior
  double front = 0;              // leading edge: max x + dx / 2
  double max_density_error = 0;  // max |rho - rho0| / rho0
  double mean_density_error = 0;
  double max_speed = 0;
};

// How the fluid is shared among the ranks of a distributed run (decomposition.h: slabs over
// MPI). Each rank owns some particles and keeps ghosts: copies of other ranks' particles near
// its own. The serial solver has none: it owns every particle and has no ghosts.
class Domain {
 public:
  virtual ~Domain() = default;
  // Once, with the initial fluid that every rank built alike: keeps this rank's particles.
  virtual void distribute(Fluid& fluid) = 0;
  // After the drift, on the owned particles (no ghosts): those now owned by another rank go
  // to it, keeping their state and id, and those arriving are appended.
  virtual void migrate(Fluid& fluid) = 0;
  // Appends, after the owned particles (no ghosts), the state of every other rank's particle
  // that lies within `width` of this rank's share of space.
  virtual void append_ghosts(Fluid& fluid, float width) = 0;
  // values[k] becomes the maximum over the ranks of values[k].
  virtual void max_over_ranks(std::span<float> values) = 0;
};

class DamBreak {
 public:
  // `domain`: the run's decomposition (it must outlive the solver); none: the serial solver.
  explicit DamBreak(const Config& config, Domain* domain = nullptr);

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

  // The owned particles, then (in a distributed run) the ghosts.
  const Fluid& fluid() const { return fluid_; }
  std::size_t owned_count() const { return owned_; }
  const Walls& walls() const { return walls_; }
  // Cell ranges of the owned particles, and of the ghosts counted from owned_count() on.
  const NeighbourGrid& fluid_grid() const { return fluid_grid_; }
  const NeighbourGrid& ghost_grid() const { return ghost_grid_; }

  // Of the owned particles: a distributed run combines the ranks' (decomposition.h).
  Diagnostics diagnostics() const;
  // Each particle's pressure (owned, then ghosts) from its current density, by the equation of
  // state the forces use, into `out` (resized): what the solver shows, not what it stores.
  void pressure(std::vector<float>& out) const;

 private:
  void drift(float dt);
  void migrate();
  void sort_fluid();
  void update_ghosts();
  void gather_state(std::size_t first, const std::vector<std::uint32_t>& permutation);
  int fluid_ranges(std::size_t cell, std::array<Range, 18>& out) const;
  void compute_fluid_pressure();
  float pressure_of(float rho) const;  // Tait's equation of state, clamped when tension-free
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
  Domain* domain_ = nullptr;
  Fluid fluid_, scratch_;
  std::size_t owned_ = 0;
  Walls walls_;
  NeighbourGrid fluid_grid_, ghost_grid_, wall_grid_;
  std::vector<std::uint32_t> permutation_;
  double time_ = 0, dt_ = 0;
  std::int64_t steps_ = 0;
};

}  // namespace dambreak
