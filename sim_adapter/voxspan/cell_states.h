// voxspan/cell_states.h - the per-cell classification of the simulation grid, as the renderer
// reads it ([ZD15] sec. 3.1 and 4.3), and the layout of the boundary-particle upload.
//
// A cell is empty, partial or full ("full" = at least the particle count of a cell filled at
// rest density). It is *inner* when it and its 26 neighbours are all empty or all full. Only
// particles of non-inner cells (boundary particles) are voxelized; the compress pass skips
// inner-empty cells and counts inner-full cells as inside. Standard library only.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace voxspan {

// One byte per cell: occupancy in bits 0-1, kInner in bit 2.
namespace cell {
constexpr std::uint8_t kEmpty = 0;
constexpr std::uint8_t kPartial = 1;
constexpr std::uint8_t kFull = 2;
constexpr std::uint8_t kOccupancyMask = 3;
constexpr std::uint8_t kInner = 4;
constexpr std::uint8_t kInnerEmpty = kInner | kEmpty;
constexpr std::uint8_t kInnerFull = kInner | kFull;

constexpr std::uint8_t occupancy(std::uint8_t state) { return state & kOccupancyMask; }
constexpr bool is_inner(std::uint8_t state) { return (state & kInner) != 0; }
}  // namespace cell

// A view of the cell states of an axis-aligned grid: cell (i, j, k) covers
// [origin + (i, j, k) * cell_size, origin + (i+1, j+1, k+1) * cell_size) and its state is
// states[i + dims[0] * (j + dims[1] * k)] (x fastest). Points outside the grid are empty air.
struct CellStatesView {
  std::array<double, 3> origin{0, 0, 0};
  double cell_size = 0;
  std::array<int, 3> dims{0, 0, 0};
  const std::uint8_t* states = nullptr;

  std::size_t cell_count() const {
    return std::size_t(dims[0]) * std::size_t(dims[1]) * std::size_t(dims[2]);
  }
  bool empty() const { return states == nullptr || cell_count() == 0; }
};

// Cell states owned (what an output keeps of a step for its writer job); view() is the
// CellStatesView of them. assign() copies a view in, keeping this storage's capacity.
struct CellStates {
  std::array<double, 3> origin{0, 0, 0};
  double cell_size = 0;
  std::array<int, 3> dims{0, 0, 0};
  std::vector<std::uint8_t> states;

  CellStatesView view() const {
    return {origin, cell_size, dims, states.empty() ? nullptr : states.data()};
  }
  void assign(const CellStatesView& v) {
    origin = v.origin;
    cell_size = v.cell_size;
    dims = v.dims;
    if (v.empty()) states.clear();
    else states.assign(v.states, v.states + v.cell_count());
  }
};

// The boundary particles handed to the renderer: packed float4 (x, y, z, radius), 16 bytes per
// particle, the std430 layout the GPU reads without conversion.
struct ParticleSphere {
  float x, y, z, radius;
};
static_assert(sizeof(ParticleSphere) == 16);

}  // namespace voxspan
