#include "cell_sort.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

#include "parallel_scan.h"

namespace voxspan::detail {
namespace {

constexpr std::size_t kGrain = 1 << 14;

template <class F> void for_ranges(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); });
}

}  // namespace

void counting_sort(std::span<const std::uint32_t> cell_of, std::size_t cell_count,
                   std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& order,
                   std::vector<std::uint32_t>& fill) {
  fill.assign(cell_count, 0);
  for_ranges(cell_of.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      if (cell_of[i] != kNoCell)
        std::atomic_ref<std::uint32_t>(fill[cell_of[i]]).fetch_add(1, std::memory_order_relaxed);
  });
  offsets.resize(cell_count + 1);
  const std::uint32_t placed = exclusive_scan(fill, offsets);

  // Scatter: fill[c] becomes the next free slot of cell c.
  std::copy(offsets.begin(), offsets.end() - 1, fill.begin());
  order.resize(placed);
  for_ranges(cell_of.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const std::uint32_t c = cell_of[i];
      if (c == kNoCell) continue;
      const std::uint32_t slot =
          std::atomic_ref<std::uint32_t>(fill[c]).fetch_add(1, std::memory_order_relaxed);
      order[slot] = static_cast<std::uint32_t>(i);
    }
  });
  // The atomics left each cell's particles in arbitrary order: restore ascending indices so
  // the result (and the boundary-particle order) is the same on every run.
  for_ranges(cell_count, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = b; c < e; ++c) {
      auto first = order.begin() + offsets[c], last = order.begin() + offsets[c + 1];
      if (last - first > 1) std::sort(first, last);
    }
  });
}

}  // namespace voxspan::detail
