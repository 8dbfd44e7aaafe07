// The counting sort behind a grid built from positions: every way it runs (one thread; a tally
// per thread; shared atomic tallies where there are more cells than particles per thread)
// gives the cells' particles in ascending index order, as a stable sort by cell does.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "sim_adapter/cell_sort.h"

namespace voxspan::detail {
namespace {

struct Sorted {
  std::vector<std::uint32_t> offsets, order;
};

Sorted stable_sort_by_cell(const std::vector<std::uint32_t>& cell_of, std::size_t cells) {
  Sorted s;
  for (std::uint32_t i = 0; i < cell_of.size(); ++i)
    if (cell_of[i] != kNoCell) s.order.push_back(i);
  std::stable_sort(s.order.begin(), s.order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return cell_of[a] < cell_of[b]; });
  s.offsets.assign(cells + 1, 0);
  for (std::uint32_t i : s.order) ++s.offsets[cell_of[i] + 1];
  std::partial_sum(s.offsets.begin(), s.offsets.end(), s.offsets.begin());
  return s;
}

// n particles in random cells, one in ten in none.
std::vector<std::uint32_t> random_cells(std::size_t n, std::size_t cells) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::uint32_t> cell(0, std::uint32_t(cells - 1));
  std::vector<std::uint32_t> cell_of(n);
  for (auto& c : cell_of) c = rng() % 10 == 0 ? kNoCell : cell(rng);
  return cell_of;
}

TEST(CellSort, EveryThreadCountAndTallyGivesTheStableOrder) {
  constexpr std::size_t n = 200000;
  for (const std::size_t cells : {std::size_t(1), std::size_t(1000), std::size_t(500000)}) {
    const std::vector<std::uint32_t> cell_of = random_cells(n, cells);
    const Sorted expected = stable_sort_by_cell(cell_of, cells);
    for (const int threads : {1, 2, 4}) {
      SCOPED_TRACE(testing::Message() << cells << " cells, " << threads << " threads");
      Sorted got;
      std::vector<std::uint32_t> scratch(7, 7);  // left over from another step
      tbb::task_arena(threads).execute(
          [&] { counting_sort(cell_of, cells, got.offsets, got.order, scratch); });
      EXPECT_EQ(got.offsets, expected.offsets);
      EXPECT_EQ(got.order, expected.order);
    }
  }
}

TEST(CellSort, NoParticlesAndNoCells) {
  Sorted got;
  std::vector<std::uint32_t> scratch;
  counting_sort({}, 5, got.offsets, got.order, scratch);
  EXPECT_EQ(got.offsets, std::vector<std::uint32_t>(6, 0));
  EXPECT_TRUE(got.order.empty());
  const std::vector<std::uint32_t> none(3, kNoCell);
  counting_sort(none, 0, got.offsets, got.order, scratch);
  EXPECT_EQ(got.offsets, std::vector<std::uint32_t>(1, 0));
  EXPECT_TRUE(got.order.empty());
}

}  // namespace
}  // namespace voxspan::detail
