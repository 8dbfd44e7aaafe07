#include "insitu/views/sph_points.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace voxspan {
namespace {

// A uniform grid of cells over the points' box grown by the support.
struct PointGrid {
  glm::dvec3 lo{0};
  double cell = 1;
  std::array<long long, 3> dims{1, 1, 1};

  int reach = 1;  // a point's particles are in the cells up to `reach` away from its own

  PointGrid(std::span<const glm::dvec3> points, double support) {
    glm::dvec3 hi(-std::numeric_limits<double>::infinity());
    lo = -hi;
    for (const glm::dvec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    lo -= support, hi += support;
    const glm::dvec3 extent = hi - lo;
    const double volume = extent.x * extent.y * extent.z;
    // Cells of half the support: 5^3 of them hold a point's particles in 1.7 times less volume
    // than 3^3 of the support's own size.
    cell = std::max(0.5 * support, std::cbrt(volume / double(SphPoints::kMaxCells)));
    reach = int(std::ceil(support / cell));
    for (int k = 0; k < 3; ++k) dims[k] = std::max(1LL, (long long)std::ceil(extent[k] / cell));
  }
  std::size_t count() const { return std::size_t(dims[0] * dims[1] * dims[2]); }
  // Clamped to one cell outside the grid, so that far particles (a solver's strays) convert.
  std::array<long long, 3> cell_of(const glm::dvec3& p) const {
    const glm::dvec3 c = glm::clamp(glm::floor((p - lo) / cell), glm::dvec3(-1),
                                    glm::dvec3(dims[0], dims[1], dims[2]));
    return {(long long)c.x, (long long)c.y, (long long)c.z};
  }
  bool inside(const std::array<long long, 3>& c) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < dims[0] && c[1] < dims[1] &&
           c[2] < dims[2];
  }
  std::size_t index(const std::array<long long, 3>& c) const {
    return std::size_t(c[0] + dims[0] * (c[1] + dims[1] * c[2]));
  }
};

}  // namespace

void interpolate_at_points(const ParticleView& particles, const SliceQuantity& q,
                           std::span<const glm::dvec3> points, SphPoints& out) {
  const double h = q.smoothing_length;
  out.sum.assign(points.size(), 0.0);
  out.weight.assign(points.size(), 0.0);
  out.particles_near = 0;
  if (points.empty()) {
    // Still checked, so that a missing attribute fails on every step, with or without fluid.
    sph_terms(
        particles, q, [](const glm::dvec3&) { return false; }, out.near);
    return;
  }
  const PointGrid grid(points, kernel_support(q.kernel) * std::max(h, 0.0));
  sph_terms(
      particles, q, [&](const glm::dvec3& p) { return grid.inside(grid.cell_of(p)); }, out.near);
  const std::vector<SphTerm>& near = out.near;
  out.particles_near = near.size();

  // Counting sort of the terms into the cells.
  const std::size_t cells = grid.count();
  std::vector<std::uint32_t>& start = out.cell_start;
  std::vector<std::uint32_t>& cell = out.cell_of;
  start.assign(cells + 1, 0);
  cell.resize(near.size());
  for (std::size_t k = 0; k < near.size(); ++k) {
    cell[k] = std::uint32_t(grid.index(grid.cell_of(near[k].p)));
    ++start[cell[k] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<std::uint32_t>& fill = out.cell_fill;
  std::vector<std::uint32_t>& sorted = out.sorted;
  fill.assign(start.begin(), start.end() - 1);
  sorted.resize(near.size());
  for (std::size_t k = 0; k < near.size(); ++k) sorted[fill[cell[k]]++] = std::uint32_t(k);

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const glm::dvec3 x = points[k];
                        const auto c = grid.cell_of(x);
                        SphSum sum;
                        const long long r = grid.reach;
                        for (long long dz = -r; dz <= r; ++dz)
                          for (long long dy = -r; dy <= r; ++dy)
                            for (long long dx = -r; dx <= r; ++dx) {
                              const std::array<long long, 3> n{c[0] + dx, c[1] + dy, c[2] + dz};
                              if (!grid.inside(n)) continue;
                              const std::size_t b = grid.index(n);
                              for (std::uint32_t s = start[b]; s < start[b + 1]; ++s)
                                sum.add(near[sorted[s]], x, q.kernel, h);
                            }
                        out.sum[k] = sum.sum;
                        out.weight[k] = sum.weight;
                      }
                    });
}

}  // namespace voxspan
