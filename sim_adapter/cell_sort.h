// cell_sort.h (internal) - the counting sort that builds a compact grid when the solver shares
// none (or only a per-particle cell index): CSR offsets per cell and the particle indices in
// cell order. Deterministic: within a cell, particles keep ascending index order.
// Costs: two passes over the particles with atomic increments, one scan over the cells, and
// a sort of each cell's few entries. Parallel with oneTBB.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace voxspan::detail {

// Marks a particle that goes into no cell (NaN position, outside the geometry).
constexpr std::uint32_t kNoCell = 0xffffffffu;

// cell_of[i] is particle i's cell (< cell_count) or kNoCell. Fills offsets (cell_count + 1
// entries) and order (one entry per placed particle); `fill` is scratch (cell_count entries).
void counting_sort(std::span<const std::uint32_t> cell_of, std::size_t cell_count,
                   std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& order,
                   std::vector<std::uint32_t>& fill);

}  // namespace voxspan::detail
