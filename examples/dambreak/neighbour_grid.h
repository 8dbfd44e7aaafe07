// neighbour_grid.h - the solver's cell-sorted neighbour grid: cells of the kernel support,
// x fastest; particles are stored sorted by cell and offsets[c] .. offsets[c+1] are cell c's.
// Because x is fastest, the three cells (i-1..i+1, j, k) are one contiguous particle range,
// so a particle's 27 neighbour cells are 9 ranges. The same arrays are handed to the in-situ
// adapter as a compact grid, without a copy.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace dambreak {

struct GridShape {
  std::array<double, 3> origin{};
  double cell_size = 0;
  std::array<int, 3> dims{};

  std::size_t cell_count() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
  // The cell of a point, clamped into the grid (a particle that left it is caught elsewhere).
  std::uint32_t cell_of(float x, float y, float z) const;
};

// A half-open range of sorted particle slots.
struct Range {
  std::uint32_t begin, end;
};

class NeighbourGrid {
 public:
  explicit NeighbourGrid(GridShape shape) : shape_(shape) {}

  // Sorts particles by cell: computes each particle's cell, counts, scans, and fills
  // `permutation` (new slot -> old index). The caller then gathers its arrays.
  void sort(const float* x, const float* y, const float* z, std::size_t n,
            std::vector<std::uint32_t>& permutation);

  // The 9 ranges covering the 27 cells around cell c (fewer at the grid's faces).
  int neighbour_ranges(std::size_t c, std::array<Range, 9>& out) const;

  const GridShape& shape() const { return shape_; }
  const std::vector<std::uint32_t>& offsets() const { return offsets_; }
  Range cell(std::size_t c) const { return {offsets_[c], offsets_[c + 1]}; }

 private:
  GridShape shape_;
  std::vector<std::uint32_t> offsets_;  // cell_count() + 1
  std::vector<std::uint32_t> cell_;     // per particle, before sorting
  std::vector<std::uint32_t> next_;     // scatter cursor per cell
};

// One cell order over two grids of one shape whose particles are stored one segment after the
// other (a rank's owned particles, then its ghosts from `second_base` on): cell c's particles
// are order[offsets[c]] .. order[offsets[c+1] - 1], those of the first segment first. What
// the in-situ adapter takes as a compact grid with an order array.
struct CellOrder {
  std::vector<std::uint32_t> offsets, order;
};
void merge_cell_orders(const NeighbourGrid& first, const NeighbourGrid& second,
                       std::uint32_t second_base, CellOrder& out);

}  // namespace dambreak
