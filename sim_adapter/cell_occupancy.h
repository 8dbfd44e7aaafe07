// cell_occupancy.h (internal) - per-cell occupancy and the inner bit from particle counts
// ([ZD15] sec. 4.3: "only inner full and empty cells may be skipped"), with a scratch
// buffer the classifier reuses between steps.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "voxspan/classify.h"

namespace voxspan::detail {

void classify_cells(const GridGeometry& geometry, std::span<const std::uint32_t> counts,
                    int full_count, std::span<std::uint8_t> states,
                    std::vector<std::uint8_t>& scratch);

// Adds the cells of each state to `counts` (cells, empty, partial, full, inner_*).
void tally_cells(std::span<const std::uint8_t> states, ClassifyCounts& counts);

}  // namespace voxspan::detail
