// Cell states and boundary particles of a scene (scenes.h), from the solver side's classifier
// (voxspan/classify.h) on a grid aligned with the origin: a cell is empty, full (>= full_count
// particle centres) or partial, inner when it and its 26 neighbours are all empty or all full
// (outside the grid is empty air); the particles of non-inner cells are the boundary particles
// ([ZD15] sec. 3.1, 5).
#pragma once

#include <cstdint>
#include <vector>

#include "voxspan/cell_states.h"

namespace voxspan::test {

struct TestCells {
  std::vector<std::uint8_t> states;
  CellStatesView view;                   // points into `states`
  std::vector<ParticleSphere> boundary;  // particles of non-inner cells
  std::int64_t inner_full_cells = 0, inner_empty_cells = 0;

  TestCells() = default;
  TestCells(const TestCells&) = delete;  // view points into states
  TestCells& operator=(const TestCells&) = delete;
  TestCells(TestCells&&) = default;
  TestCells& operator=(TestCells&&) = default;
};

// Cells of side cell_size on a lattice aligned with the origin (so a particle lattice with
// spacing cell_size / 2 from the origin puts 8 particles in each full cell), covering the
// particles with one cell of margin.
TestCells classify_for_test(const std::vector<ParticleSphere>& particles, double cell_size,
                            int full_count);

}  // namespace voxspan::test
