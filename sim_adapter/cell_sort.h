// cell_sort.h (internal) - the counting sort that builds a compact grid when the solver shares
// none (or only a per-particle cell index): CSR offsets per cell and the particle indices in
// cell order. Deterministic: within a cell, particles keep ascending index order.
// Costs: two passes over the particles, one scan over the cells. Parallel with oneTBB: each
// thread tallies its own share of the particles (one counter per cell and thread) where those
// counters number at most two per particle; with more cells than that, one shared tally of
// atomic increments and a sort of each cell's few entries.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace voxspan::detail {

// Marks a particle that goes into no cell (NaN position, outside the geometry).
constexpr std::uint32_t kNoCell = 0xffffffffu;

// cell_of[i] is particle i's cell (< cell_count) or kNoCell. Fills offsets (cell_count + 1
// entries) and order (one entry per placed particle); `scratch` holds the tallies.
void counting_sort(std::span<const std::uint32_t> cell_of, std::size_t cell_count,
                   std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& order,
                   std::vector<std::uint32_t>& scratch);

}  // namespace voxspan::detail
