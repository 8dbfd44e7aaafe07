// Counting sort of the particles into cells. The particles were sorted last step and move less
// than a cell per step, so the scatter walks memory almost in order.
#include "neighbour_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace dambreak {

std::uint32_t GridShape::cell_of(float x, float y, float z) const {
  const float p[3] = {x, y, z};
  int ijk[3];
  for (int a = 0; a < 3; ++a) {
    const double f = std::floor((double(p[a]) - origin[a]) / cell_size);
    ijk[a] = f < 0 ? 0 : f >= dims[a] ? dims[a] - 1 : int(f);  // NaN -> 0, caught by the solver
  }
  return std::uint32_t(ijk[0] + std::size_t(dims[0]) * (ijk[1] + std::size_t(dims[1]) * ijk[2]));
}

void NeighbourGrid::sort(const float* x, const float* y, const float* z, std::size_t n,
                         std::vector<std::uint32_t>& permutation) {
  const std::size_t cells = shape_.cell_count();
  cell_.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        cell_[i] = shape_.cell_of(x[i], y[i], z[i]);
                    });
  offsets_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++offsets_[cell_[i] + 1];
  for (std::size_t c = 0; c < cells; ++c) offsets_[c + 1] += offsets_[c];
  next_.assign(offsets_.begin(), offsets_.end() - 1);
  permutation.resize(n);
  for (std::size_t i = 0; i < n; ++i) permutation[next_[cell_[i]]++] = std::uint32_t(i);
}

int NeighbourGrid::neighbour_ranges(std::size_t c, std::array<Range, 9>& out) const {
  const int nx = shape_.dims[0], ny = shape_.dims[1], nz = shape_.dims[2];
  const int i = int(c % std::size_t(nx)), j = int((c / std::size_t(nx)) % std::size_t(ny)),
            k = int(c / (std::size_t(nx) * std::size_t(ny)));
  const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, nx - 1);
  int count = 0;
  for (int kk = std::max(k - 1, 0); kk <= std::min(k + 1, nz - 1); ++kk)
    for (int jj = std::max(j - 1, 0); jj <= std::min(j + 1, ny - 1); ++jj) {
      const std::size_t row =
          std::size_t(nx) * (std::size_t(jj) + std::size_t(ny) * std::size_t(kk));
      const Range r{offsets_[row + std::size_t(i0)], offsets_[row + std::size_t(i1) + 1]};
      if (r.begin != r.end) out[std::size_t(count++)] = r;
    }
  return count;
}

void merge_cell_orders(const NeighbourGrid& first, const NeighbourGrid& second,
                       std::uint32_t second_base, CellOrder& out) {
  const std::vector<std::uint32_t>&a = first.offsets(), &b = second.offsets();
  out.offsets.resize(a.size());
  out.order.resize(a.back() + b.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, a.size() - 1, 1 << 10),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c != r.end(); ++c) {
                        std::uint32_t k = out.offsets[c] = a[c] + b[c];
                        for (std::uint32_t i = a[c]; i < a[c + 1]; ++i) out.order[k++] = i;
                        for (std::uint32_t i = b[c]; i < b[c + 1]; ++i)
                          out.order[k++] = second_base + i;
                      }
                    });
  out.offsets.back() = a.back() + b.back();
}

}  // namespace dambreak
