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

// The cells within grid.reach of a point's cell along every axis: those whose particles some
// point reads (sum_at), so that the others' particles (the fluid's inside, far from its first
// surface) are not even sorted. The points' cells marked, then widened by the reach one axis at
// a time (a cube is the product of its axes' ranges).
const std::vector<std::uint8_t>& reached_cells(const PointGrid& grid,
                                               std::span<const glm::dvec3> points, SphPoints& out) {
  std::vector<std::uint8_t>& marks = out.cell_reached;
  std::vector<std::uint8_t>& widened = out.cell_widened;
  marks.assign(grid.count(), 0);
  for (const glm::dvec3& p : points) marks[grid.index(grid.cell_of(p))] = 1;
  const long long stride[3] = {1, grid.dims[0], grid.dims[0] * grid.dims[1]};
  for (int axis = 0; axis < 3; ++axis) {
    widened.assign(marks.size(), 0);
    const long long n = grid.dims[axis], r = grid.reach;
    for (std::size_t k = 0; k < marks.size(); ++k) {
      if (marks[k] == 0) continue;
      const long long i = (long long)(k) / stride[axis] % n;
      for (long long j = std::max(i - r, 0LL); j <= std::min(i + r, n - 1); ++j)
        widened[std::size_t((long long)(k) + (j - i) * stride[axis])] = 1;
    }
    marks.swap(widened);
  }
  return marks;
}

// Squared distance from t to the interval of cell index i along an axis starting at lo.
double gap_squared(double t, long long i, double lo, double cell) {
  const double a = lo + double(i) * cell, b = a + cell;
  const double d = t < a ? a - t : t > b ? t - b : 0.0;
  return d * d;
}

// The sums at x over the cells up to grid.reach away from its own, each row of cells (along x)
// one run of `sorted` from `start`; rows the support's sphere cannot reach (the 5x5x5 block's
// corner rows) are skipped: their particles add nothing. Trimming each row to the sphere too
// took fewer instructions but more time (a square root and two divisions per row).
SphSum sum_at(const PointGrid& grid, std::span<const std::uint32_t> start,
              std::span<const SphTerm> sorted, const glm::dvec3& x, const SliceQuantity& q,
              double h) {
  const auto c = grid.cell_of(x);
  const long long r = grid.reach;
  const double support = kernel_support(q.kernel) * h, support2 = support * support;
  SphSum sum;
  for (long long z = std::max(c[2] - r, 0LL); z <= std::min(c[2] + r, grid.dims[2] - 1); ++z) {
    const double gz = gap_squared(x.z, z, grid.lo.z, grid.cell);
    for (long long y = std::max(c[1] - r, 0LL); y <= std::min(c[1] + r, grid.dims[1] - 1); ++y) {
      const double g = gz + gap_squared(x.y, y, grid.lo.y, grid.cell);
      if (g >= support2) continue;
      const long long x0 = std::max(c[0] - r, 0LL), x1 = std::min(c[0] + r, grid.dims[0] - 1);
      if (x0 > x1) continue;
      const std::size_t row = grid.index({0, y, z});
      for (std::uint32_t s = start[row + std::size_t(x0)]; s < start[row + std::size_t(x1) + 1];
           ++s)
        sum.add(sorted[s], x, q, h);
    }
  }
  return sum;
}

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
        particles, q, [](const glm::dvec3&, double) { return false; }, out.near);
    return;
  }
  const PointGrid grid(points, kernel_support(q.kernel) * std::max(h, 0.0));
  const std::vector<std::uint8_t>& reached = reached_cells(grid, points, out);
  sph_terms(
      particles, q,
      [&](const glm::dvec3& p, double) {
        const auto c = grid.cell_of(p);
        return grid.inside(c) && reached[grid.index(c)] != 0;
      },
      out.near);
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
  // The terms themselves in cell order: a point reads each row of its cells as one run of
  // memory.
  std::vector<std::uint32_t>& fill = out.cell_fill;
  std::vector<SphTerm>& sorted = out.sorted;
  fill.assign(start.begin(), start.end() - 1);
  sorted.resize(near.size());
  for (std::size_t k = 0; k < near.size(); ++k) sorted[fill[cell[k]]++] = near[k];

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const SphSum sum = sum_at(grid, start, sorted, points[k], q, h);
                        out.sum[k] = sum.sum;
                        out.weight[k] = sum.weight;
                      }
                    });
}

}  // namespace voxspan
