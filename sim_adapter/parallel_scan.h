// parallel_scan.h (internal) - exclusive prefix sums over per-cell counts, parallel with
// oneTBB. Used by the counting sort (cell offsets) and by compaction (output offsets).
#pragma once

#include <cstdint>
#include <span>

namespace voxspan::detail {

// out[i] = in[0] + ... + in[i-1] for i in [0, in.size()], so out has in.size() + 1 entries;
// returns the total. `in` and `out` may be the same storage shifted by nothing (in place is
// fine: out[i] is written after in[i] is read). Throws voxspan::Error if the total does not
// fit 32 bits.
std::uint32_t exclusive_scan(std::span<const std::uint32_t> in, std::span<std::uint32_t> out);

}  // namespace voxspan::detail
