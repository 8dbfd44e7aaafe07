// particle_sets.h - particle sets and grids built by hand for the classification tests: lattice
// blocks, droplets, noisy clouds, and the solver-side grids (CSR, begin/end, cell index) the
// tests hand to the classifier.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "voxspan/classify.h"

namespace voxspan::test {

struct Point {
  float x, y, z;
};

// A cubic lattice of spacing `dx` filling [lo, lo + n * dx) per axis, particle centres at
// half spacings.
inline void add_lattice(std::vector<Point>& pts, std::array<double, 3> lo, std::array<int, 3> n,
                        double dx) {
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        pts.push_back({float(lo[0] + (i + 0.5) * dx), float(lo[1] + (j + 0.5) * dx),
                       float(lo[2] + (k + 0.5) * dx)});
}

// A block, two droplets and a spray of single particles, jittered: every kind of cell.
inline std::vector<Point> noisy_scene(unsigned seed) {
  std::vector<Point> pts;
  add_lattice(pts, {4, 4, 4}, {14, 10, 12}, 1.0);
  add_lattice(pts, {24, 6, 6}, {3, 3, 3}, 1.0);
  add_lattice(pts, {8, 20, 8}, {2, 1, 2}, 1.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.2f, 0.2f), anywhere(0.5f, 29.5f);
  for (Point& p : pts) {
    p.x += jitter(rng);
    p.y += jitter(rng);
    p.z += jitter(rng);
  }
  for (int s = 0; s < 40; ++s) pts.push_back({anywhere(rng), anywhere(rng), anywhere(rng)});
  std::shuffle(pts.begin(), pts.end(), rng);
  return pts;
}

inline GridGeometry cube_grid(double cell_size, int cells_per_axis) {
  GridGeometry g;
  g.cell_size = cell_size;
  g.dims = {cells_per_axis, cells_per_axis, cells_per_axis};
  return g;
}

inline std::uint32_t cell_of(const GridGeometry& g, const Point& p) {
  auto axis = [&](float v, int a) {
    const int c = int(std::floor((double(v) - g.origin[std::size_t(a)]) / g.cell_size));
    return std::clamp(c, 0, g.dims[std::size_t(a)] - 1);
  };
  return std::uint32_t(g.linear(axis(p.x, 0), axis(p.y, 1), axis(p.z, 2)));
}

// What a solver with a compact grid keeps: its particles stored in cell order (stable), CSR
// offsets, and the permutation from sorted slot to original index.
struct SortedGrid {
  std::vector<Point> sorted;
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> order;  // sorted slot -> index in the unsorted input
  std::vector<std::uint32_t> cells;  // per unsorted particle
};

inline SortedGrid sort_into(const GridGeometry& g, const std::vector<Point>& pts) {
  SortedGrid s;
  s.offsets.assign(g.cell_count() + 1, 0);
  for (const Point& p : pts) {
    s.cells.push_back(cell_of(g, p));
    ++s.offsets[s.cells.back() + 1];
  }
  for (std::size_t c = 0; c < g.cell_count(); ++c) s.offsets[c + 1] += s.offsets[c];
  std::vector<std::uint32_t> next(s.offsets.begin(), s.offsets.end() - 1);
  s.order.resize(pts.size());
  for (std::uint32_t i = 0; i < pts.size(); ++i) s.order[next[s.cells[i]]++] = i;
  for (std::uint32_t i : s.order) s.sorted.push_back(pts[i]);
  return s;
}

// The boundary spheres as a sorted list, to compare results whose order may differ.
inline std::vector<std::array<float, 4>> sorted_spheres(const Classification& c) {
  std::vector<std::array<float, 4>> v;
  for (const ParticleSphere& s : c.boundary) v.push_back({s.x, s.y, s.z, s.radius});
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace voxspan::test
