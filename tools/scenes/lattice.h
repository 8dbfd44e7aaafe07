// A block of particles on a cubic lattice and its cell states, computed here from first
// principles (count per cell; inner = the cell and its 26 neighbours agree), so that the
// snapshot tests do not depend on the solver side's classification; bench_runtime times the
// runtime on the same kind of block.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "voxspan/cell_states.h"

namespace voxspan::test {

struct LatticeScene {
  double spacing = 0;          // particle spacing dx
  int particles_per_side = 0;  // n: the block holds n^3 particles
  std::vector<ParticleSphere> all;
  std::vector<ParticleSphere> boundary;       // the particles of non-inner cells
  std::vector<std::uint32_t> boundary_index;  // their indices into `all`
  std::array<double, 3> origin{};
  double cell_size = 0;
  std::array<int, 3> dims{};
  std::vector<std::uint8_t> states;
  CellStatesView cells() const { return {origin, cell_size, dims, states.data()}; }
  std::size_t count_state(std::uint8_t s) const {
    std::size_t c = 0;
    for (auto v : states) c += v == s;
    return c;
  }
};

// n^3 particles at (i + 0.5) * dx, i = 0..n-1, radius `radius`; cells of 2 dx (8 particles
// when full) with `margin` empty cells around the block.
inline LatticeScene make_lattice_block(int n, double dx, float radius, int margin = 2) {
  LatticeScene s;
  s.spacing = dx;
  s.particles_per_side = n;
  s.cell_size = 2 * dx;
  int block_cells = (n + 1) / 2;
  for (int a = 0; a < 3; ++a) {
    s.origin[a] = -margin * s.cell_size;
    s.dims[a] = block_cells + 2 * margin;
  }
  auto cell_index = [&](int i, int j, int k) {
    return std::size_t(i) + std::size_t(s.dims[0]) * (std::size_t(j) + std::size_t(s.dims[1]) * k);
  };
  std::vector<int> counts(std::size_t(s.dims[0]) * s.dims[1] * s.dims[2], 0);
  std::vector<std::size_t> cell_of;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        ParticleSphere p{float((i + 0.5) * dx), float((j + 0.5) * dx), float((k + 0.5) * dx),
                         radius};
        s.all.push_back(p);
        std::size_t c = cell_index(int((p.x - s.origin[0]) / s.cell_size),
                                   int((p.y - s.origin[1]) / s.cell_size),
                                   int((p.z - s.origin[2]) / s.cell_size));
        ++counts[c];
        cell_of.push_back(c);
      }
  const int full = 8;
  s.states.resize(counts.size());
  for (std::size_t c = 0; c < counts.size(); ++c)
    s.states[c] = counts[c] == 0 ? cell::kEmpty : counts[c] >= full ? cell::kFull : cell::kPartial;
  std::vector<std::uint8_t> inner(counts.size(), 0);
  for (int k = 0; k < s.dims[2]; ++k)
    for (int j = 0; j < s.dims[1]; ++j)
      for (int i = 0; i < s.dims[0]; ++i) {
        std::uint8_t own = s.states[cell_index(i, j, k)];
        if (own == cell::kPartial) continue;
        bool agree = true;
        for (int dk = -1; dk <= 1 && agree; ++dk)
          for (int dj = -1; dj <= 1 && agree; ++dj)
            for (int di = -1; di <= 1 && agree; ++di) {
              int a = i + di, b = j + dj, c = k + dk;
              bool outside =
                  a < 0 || b < 0 || c < 0 || a >= s.dims[0] || b >= s.dims[1] || c >= s.dims[2];
              std::uint8_t other = outside ? cell::kEmpty : s.states[cell_index(a, b, c)];
              agree = other == own;
            }
        if (agree) inner[cell_index(i, j, k)] = cell::kInner;
      }
  for (std::size_t c = 0; c < counts.size(); ++c) s.states[c] |= inner[c];
  for (std::size_t p = 0; p < s.all.size(); ++p)
    if (!cell::is_inner(s.states[cell_of[p]])) {
      s.boundary.push_back(s.all[p]);
      s.boundary_index.push_back(std::uint32_t(p));
    }
  return s;
}

}  // namespace voxspan::test
