// scene.h - the dam-break set-up of Martin & Moyce (1952): a water column of width a and
// height 2a (n^2 = 2) at rest against the left wall of a closed tank, released at t = 0.
// x runs along the tank, y across it, z up; the column spans the tank's whole depth (as in
// the experiment), so the flow is 3D with a 2D mean. A thin tank (depth_particles > 0) is
// the cheap quasi-2D version the tests run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dambreak {

struct Config {
  double column_width = 0.05715;   // a in metres: Martin & Moyce's 2.25 in column
  double depth_ratio = 1.0;        // tank and column depth (y) in units of a
  int depth_particles = 0;         // > 0: the depth in particles instead (thin tank)
  std::size_t particles = 100000;  // fluid particles wanted (the count is rounded to a lattice)
  double tank_length = 4.0;        // in units of a
  double tank_height = 3.0;        // in units of a; the tank has a lid
  int wall_layers = 3;             // enough to fill the kernel support at the walls

  double rest_density = 1000;      // kg/m^3
  double gravity = 9.81;           // m/s^2
  double h_over_dx = 1.2;          // smoothing length in particle spacings
  double sound_speed_factor = 10;  // c0 = factor * sqrt(2 g H): density varies ~1 %
  double alpha = 0.02;             // artificial viscosity (Monaghan 1992)
  double delta = 0.1;              // density diffusion (delta-SPH, Molteni & Colagrossi 2009)
  double cfl = 0.25;               // dt = cfl * h / (c0 + max |v|)
  bool wall_viscosity = true;      // artificial viscosity against the walls too (wall friction)
  // The liquid sustains no tension: p >= 0 and rho >= rho0. Without it a free surface under
  // tension clumps and explodes (tensile instability), and spray that separates keeps a low
  // continuity density, falls back without pressure and collapses onto the fluid.
  bool tension_free = true;
};

// Lattice counts and spacing derived from a Config.
struct Lattice {
  double dx = 0;
  int column_x = 0, column_z = 0;  // column particles along x and z (column_z = 2 column_x)
  int depth = 0;                   // particles across the tank (y)
  int tank_x = 0, tank_z = 0;      // tank interior in spacings
  std::size_t fluid_count() const { return std::size_t(column_x) * depth * column_z; }
};

Lattice make_lattice(const Config& config);

struct Points {
  std::vector<float> x, y, z;
  void add(double px, double py, double pz) {
    x.push_back(float(px));
    y.push_back(float(py));
    z.push_back(float(pz));
  }
};

// Particle centres at half spacings: the column, and the wall shell around the tank interior
// [0, tank_x dx] x [0, depth dx] x [0, tank_z dx].
Points column_particles(const Lattice& lattice);
Points wall_particles(const Lattice& lattice, int layers);

}  // namespace dambreak
