#include "tools/common/rank_split.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace voxspan::tools {
namespace {

// The axis along which the finite positions spread most.
int longest_axis(std::span<const std::array<double, 3>> p) {
  std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const auto& q : p)
    for (int a = 0; a < 3; ++a)
      if (std::isfinite(q[std::size_t(a)])) {
        lo[std::size_t(a)] = std::min(lo[std::size_t(a)], q[std::size_t(a)]);
        hi[std::size_t(a)] = std::max(hi[std::size_t(a)], q[std::size_t(a)]);
      }
  int best = 0;
  for (int a = 1; a < 3; ++a)
    if (hi[std::size_t(a)] - lo[std::size_t(a)] > hi[std::size_t(best)] - lo[std::size_t(best)])
      best = a;
  return best;
}

// Where rank r's share of the sorted particles begins, in [0, n]: equal shares, or for
// `uneven` shares growing 1, 2, 3... with the last rank's empty.
std::size_t share_begin(std::size_t n, Split split, int r, int ranks) {
  if (split != Split::uneven || ranks == 1) return n * std::size_t(r) / std::size_t(ranks);
  const std::size_t parts = std::size_t(ranks - 1) * std::size_t(ranks) / 2;  // 1 + ... + N-1
  const std::size_t before =
      std::size_t(std::min(r, ranks - 1)) * std::size_t(std::min(r, ranks - 1) + 1) / 2;
  return std::min(n, n * before / parts);
}

}  // namespace

RankPart split_particles(std::span<const std::array<double, 3>> positions, Split split, int rank,
                         int ranks, double margin) {
  RankPart part;
  const std::size_t n = positions.size();
  if (split == Split::interleaved) {
    for (std::size_t i = std::size_t(rank); i < n; i += std::size_t(ranks))
      part.indices.push_back(i);
    part.owned = part.indices.size();
    for (std::size_t i = 0; i < n; ++i)
      if (i % std::size_t(ranks) != std::size_t(rank)) part.indices.push_back(i);
    return part;
  }
  const int axis = longest_axis(positions);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  // Non-finite positions sort last and go to the last rank with a share: it reports them.
  auto key = [&](std::size_t i) {
    const double v = positions[i][std::size_t(axis)];
    return std::isfinite(v) ? v : HUGE_VAL;
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  const std::size_t begin = share_begin(n, split, rank, ranks);
  const std::size_t end = share_begin(n, split, rank + 1, ranks);
  part.indices.assign(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(end));
  part.owned = part.indices.size();
  if (begin == end) return part;
  const double lo = key(order[begin]) - margin, hi = key(order[end - 1]) + margin;
  for (std::size_t k = 0; k < n; ++k) {
    if (k >= begin && k < end) continue;
    const double v = key(order[k]);
    if (v >= lo && v <= hi && std::isfinite(v)) part.indices.push_back(order[k]);
  }
  return part;
}

}  // namespace voxspan::tools
