#include "insitu/io/spacing_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace voxspan {
namespace {

bool finite(const std::array<double, 3>& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

constexpr std::size_t kFullSearchLimit = 4096;

double nearest_by_full_search(std::span<const std::array<double, 3>> positions, std::size_t i) {
  const auto& p = positions[i];
  double best = std::numeric_limits<double>::infinity();
  for (const auto& q : positions) {
    if (!finite(q)) continue;
    const double d = std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
    if (d > 0) best = std::min(best, d);
  }
  return best;
}

}  // namespace

double estimate_particle_spacing(std::span<const std::array<double, 3>> positions,
                                 std::size_t samples) {
  std::array<double, 3> lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::max()};
  std::array<double, 3> hi{-lo[0], -lo[1], -lo[2]};
  std::size_t n = 0;
  for (const auto& p : positions) {
    if (!finite(p)) continue;
    ++n;
    for (std::size_t a = 0; a < 3; ++a)
      lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  }
  if (n < 2) return 0;
  // Cells of about one mean spacing: flat or thin sets count only their extended axes.
  const double largest = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (!(largest > 0)) return 0;
  double measure = 1;
  int dims = 0;
  for (std::size_t a = 0; a < 3; ++a)
    if (hi[a] - lo[a] > 1e-6 * largest) measure *= hi[a] - lo[a], ++dims;
  const double cell = std::pow(measure / double(n), 1.0 / dims);
  auto key = [&](const std::array<double, 3>& p, int dx, int dy, int dz) {
    const auto i = std::int64_t(std::floor((p[0] - lo[0]) / cell)) + dx;
    const auto j = std::int64_t(std::floor((p[1] - lo[1]) / cell)) + dy;
    const auto k = std::int64_t(std::floor((p[2] - lo[2]) / cell)) + dz;
    return (i * 73856093) ^ (j * 19349663) ^ (k * 83492791);
  };
  std::unordered_multimap<std::int64_t, std::size_t> grid;
  grid.reserve(n);
  for (std::size_t i = 0; i < positions.size(); ++i)
    if (finite(positions[i])) grid.emplace(key(positions[i], 0, 0, 0), i);

  std::vector<double> nearest;
  const std::size_t stride = std::max<std::size_t>(1, positions.size() / samples);
  for (std::size_t i = 0; i < positions.size(); i += stride) {
    const auto& p = positions[i];
    if (!finite(p)) continue;
    double best = std::numeric_limits<double>::infinity();
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto range = grid.equal_range(key(p, dx, dy, dz));
          for (auto it = range.first; it != range.second; ++it) {
            if (it->second == i) continue;
            const auto& q = positions[it->second];
            const double d = std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
            if (d > 0) best = std::min(best, d);
          }
        }
    // A sample alone in its neighbourhood (two particles far apart, a sparse line): in a small
    // set its nearest neighbour is found by a full search, or the estimate would be the cell.
    if (!std::isfinite(best) && n <= kFullSearchLimit) best = nearest_by_full_search(positions, i);
    if (std::isfinite(best)) nearest.push_back(best);
  }
  if (nearest.empty()) return cell;  // every sample alone in its neighbourhood: the mean spacing
  std::nth_element(nearest.begin(), nearest.begin() + std::ptrdiff_t(nearest.size() / 2),
                   nearest.end());
  return nearest[nearest.size() / 2];
}

std::optional<double> spacing_from_volumes(std::vector<double> volumes, int dims) {
  std::erase_if(volumes, [](double v) { return !(v > 0) || !std::isfinite(v); });
  if (volumes.empty()) return std::nullopt;
  const auto middle = volumes.begin() + std::ptrdiff_t(volumes.size() / 2);
  std::nth_element(volumes.begin(), middle, volumes.end());
  return std::pow(*middle, 1.0 / dims);
}

}  // namespace voxspan
