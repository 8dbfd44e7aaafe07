#include "cell_sort.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <utility>

#include "parallel_scan.h"

namespace voxspan::detail {
namespace {

constexpr std::size_t kGrain = 1 << 14;

template <class F> void for_ranges(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); });
}

// Block b of `blocks` equal shares of [0, n).
std::size_t block_begin(std::size_t b, std::size_t blocks, std::size_t n) {
  return n / blocks * b + std::min(b, n % blocks);
}

// How many blocks tally with plain increments: one per thread, each of kGrain particles at
// least, their counters (blocks x cells) at most two per particle; 0 where that leaves fewer
// than half the threads a block: shared atomic tallies then. Plain increments win even where no
// two threads meet: a locked increment is a full fence on x86, so a thread waits out each of
// its cache misses in turn instead of overlapping them.
std::size_t block_count(std::size_t particles, std::size_t cells) {
  const std::size_t threads = std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  const std::size_t wanted = std::min(threads, std::max<std::size_t>(1, particles / kGrain));
  if (wanted == 1) return 1;
  const std::size_t blocks = cells > 0 ? std::min(wanted, 2 * particles / cells) : wanted;
  return 2 * blocks >= wanted ? blocks : 0;
}

// Each block tallies and places its own particles with plain increments, so within a cell the
// particles keep their index order with no sort; cell c's slots start after the earlier
// blocks' particles of c. tally holds blocks x cells counters.
void sort_in_blocks(std::span<const std::uint32_t> cell_of, std::size_t cells, std::size_t blocks,
                    std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& order,
                    std::vector<std::uint32_t>& tally) {
  const std::size_t n = cell_of.size();
  tally.assign(blocks * cells, 0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    std::uint32_t* t = tally.data() + b * cells;
    for (std::size_t i = block_begin(b, blocks, n); i < block_begin(b + 1, blocks, n); ++i)
      if (cell_of[i] != kNoCell) ++t[cell_of[i]];
  });
  // offsets[c] holds cell c's count for the scan; each block's tally becomes its first slot
  // in c relative to the cell's start.
  offsets.resize(cells + 1);
  for_ranges(cells, [&](std::size_t first, std::size_t last) {
    for (std::size_t c = first; c < last; ++c) {
      std::uint32_t sum = 0;
      for (std::size_t b = 0; b < blocks; ++b) sum += std::exchange(tally[b * cells + c], sum);
      offsets[c] = sum;
    }
  });
  order.resize(exclusive_scan(std::span(offsets).first(cells), offsets));
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    std::uint32_t* next = tally.data() + b * cells;
    for (std::size_t i = block_begin(b, blocks, n); i < block_begin(b + 1, blocks, n); ++i) {
      const std::uint32_t c = cell_of[i];
      if (c != kNoCell) order[offsets[c] + next[c]++] = static_cast<std::uint32_t>(i);
    }
  });
}

// Many cells for few particles per thread: one shared tally with atomic increments, then each
// cell's entries sorted back into index order (the atomics leave them in any order).
void sort_with_atomics(std::span<const std::uint32_t> cell_of, std::size_t cells,
                       std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& order,
                       std::vector<std::uint32_t>& fill) {
  fill.assign(cells, 0);
  for_ranges(cell_of.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      if (cell_of[i] != kNoCell)
        std::atomic_ref<std::uint32_t>(fill[cell_of[i]]).fetch_add(1, std::memory_order_relaxed);
  });
  offsets.resize(cells + 1);
  order.resize(exclusive_scan(fill, offsets));
  std::copy(offsets.begin(), offsets.end() - 1, fill.begin());  // fill[c]: c's next free slot
  for_ranges(cell_of.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const std::uint32_t c = cell_of[i];
      if (c == kNoCell) continue;
      const std::uint32_t slot =
          std::atomic_ref<std::uint32_t>(fill[c]).fetch_add(1, std::memory_order_relaxed);
      order[slot] = static_cast<std::uint32_t>(i);
    }
  });
  for_ranges(cells, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = b; c < e; ++c) {
      auto first = order.begin() + offsets[c], last = order.begin() + offsets[c + 1];
      if (last - first > 1) std::sort(first, last);
    }
  });
}

}  // namespace

void counting_sort(std::span<const std::uint32_t> cell_of, std::size_t cell_count,
                   std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& order,
                   std::vector<std::uint32_t>& scratch) {
  if (const std::size_t blocks = block_count(cell_of.size(), cell_count); blocks > 0)
    sort_in_blocks(cell_of, cell_count, blocks, offsets, order, scratch);
  else sort_with_atomics(cell_of, cell_count, offsets, order, scratch);
}

}  // namespace voxspan::detail
