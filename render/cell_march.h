// render/cell_march.h - walks a pixel's ray through the simulation grid's cells in depth order
// (3D DDA, Amanatides & Woo), the march of [ZD15] sec. 4.3. CPU version, in double, for the
// exact reference; render/gl/passes/cell_march.glsl is the GPU's, with the same cell rule.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

#include "voxspan/cell_states.h"

namespace voxspan {

// Calls visit(state, z_in, z_out) for every cell of `cells` that the ray eye + z * ray meets
// for z in [z0, z1], in increasing z. Points outside the grid are empty air and not visited.
template <class Visit>
void march_cells(const CellStatesView& cells, glm::dvec3 eye, glm::dvec3 ray, double z0, double z1,
                 Visit&& visit) {
  if (cells.empty() || !(cells.cell_size > 0)) return;
  const double h = cells.cell_size;
  const glm::dvec3 origin(cells.origin[0], cells.origin[1], cells.origin[2]);
  const glm::ivec3 dims(cells.dims[0], cells.dims[1], cells.dims[2]);
  // Clip [z0, z1] to the grid's box.
  for (int a = 0; a < 3; ++a) {
    const double lo = origin[a], hi = origin[a] + dims[a] * h;
    if (ray[a] == 0) {
      if (eye[a] < lo || eye[a] >= hi) return;
      continue;
    }
    double ta = (lo - eye[a]) / ray[a], tb = (hi - eye[a]) / ray[a];
    if (ta > tb) std::swap(ta, tb);
    z0 = std::max(z0, ta);
    z1 = std::min(z1, tb);
  }
  if (!(z0 < z1)) return;
  const glm::dvec3 start = (eye + z0 * ray - origin) / h;
  glm::ivec3 cell, step;
  glm::dvec3 next, delta;
  for (int a = 0; a < 3; ++a) {
    cell[a] = std::clamp(static_cast<int>(std::floor(start[a])), 0, dims[a] - 1);
    step[a] = ray[a] > 0 ? 1 : -1;
    if (ray[a] == 0) {
      next[a] = delta[a] = std::numeric_limits<double>::infinity();
    } else {
      const double boundary = origin[a] + (cell[a] + (ray[a] > 0 ? 1 : 0)) * h;
      next[a] = (boundary - eye[a]) / ray[a];
      delta[a] = h / std::abs(ray[a]);
    }
  }
  double z = z0;
  while (z < z1) {
    const int a = next.x < next.y ? (next.x < next.z ? 0 : 2) : (next.y < next.z ? 1 : 2);
    const double z_out = std::min(next[a], z1);
    const std::size_t index =
        static_cast<std::size_t>(cell.x) +
        static_cast<std::size_t>(dims.x) *
            (static_cast<std::size_t>(cell.y) +
             static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(cell.z));
    if (z_out > z) visit(cells.states[index], z, z_out);
    z = z_out;
    cell[a] += step[a];
    next[a] += delta[a];
    if (cell[a] < 0 || cell[a] >= dims[a]) break;
  }
}

}  // namespace voxspan
