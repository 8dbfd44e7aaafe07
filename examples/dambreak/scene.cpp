#include "scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dambreak {

Lattice make_lattice(const Config& c) {
  if (c.particles < 8) throw std::invalid_argument("at least 8 particles are needed");
  if (!(c.column_width > 0) || !(c.depth_ratio > 0) || c.depth_particles < 0)
    throw std::invalid_argument("column width and depth must be > 0");
  Lattice l;
  // particles = column_x * depth * 2 column_x, with depth = depth_ratio * column_x or fixed.
  const double n = double(c.particles);
  l.column_x = c.depth_particles > 0
                   ? std::max(2, int(std::lround(std::sqrt(n / (2.0 * c.depth_particles)))))
                   : std::max(2, int(std::lround(std::cbrt(n / (2.0 * c.depth_ratio)))));
  l.column_z = 2 * l.column_x;
  l.dx = c.column_width / l.column_x;
  l.depth = c.depth_particles > 0 ? c.depth_particles
                                  : std::max(1, int(std::lround(c.depth_ratio * l.column_x)));
  l.tank_x = std::max(l.column_x + 1, int(std::lround(c.tank_length * l.column_x)));
  l.tank_z = std::max(l.column_z + 1, int(std::lround(c.tank_height * l.column_x)));
  return l;
}

Points column_particles(const Lattice& l) {
  Points p;
  for (int k = 0; k < l.column_z; ++k)
    for (int j = 0; j < l.depth; ++j)
      for (int i = 0; i < l.column_x; ++i)
        p.add((i + 0.5) * l.dx, (j + 0.5) * l.dx, (k + 0.5) * l.dx);
  return p;
}

Points wall_particles(const Lattice& l, int layers) {
  Points p;
  const int n[3] = {l.tank_x, l.depth, l.tank_z};
  for (int k = -layers; k < n[2] + layers; ++k)
    for (int j = -layers; j < n[1] + layers; ++j)
      for (int i = -layers; i < n[0] + layers; ++i) {
        const bool inside = i >= 0 && i < n[0] && j >= 0 && j < n[1] && k >= 0 && k < n[2];
        if (!inside) p.add((i + 0.5) * l.dx, (j + 0.5) * l.dx, (k + 0.5) * l.dx);
      }
  return p;
}

}  // namespace dambreak
