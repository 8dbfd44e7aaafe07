#include "scene_cell_states.h"

#include <algorithm>
#include <cmath>

namespace voxspan::test {

TestCells classify_for_test(const std::vector<ParticleSphere>& particles, double h,
                            int full_count) {
  TestCells out;
  if (particles.empty()) return out;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const ParticleSphere& p : particles) {
    const double c[3] = {p.x, p.y, p.z};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
  }
  CellStatesView& v = out.view;
  v.cell_size = h;
  for (int a = 0; a < 3; ++a) {
    v.origin[a] = (std::floor(lo[a] / h) - 1) * h;
    v.dims[a] = static_cast<int>(std::floor((hi[a] - v.origin[a]) / h)) + 2;
  }
  const auto index = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(v.dims[0]) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(v.dims[1]) * k);
  };
  const auto cell_of = [&](const ParticleSphere& p) {
    const double c[3] = {p.x, p.y, p.z};
    int ijk[3];
    for (int a = 0; a < 3; ++a)
      ijk[a] = std::clamp(static_cast<int>(std::floor((c[a] - v.origin[a]) / h)), 0, v.dims[a] - 1);
    return index(ijk[0], ijk[1], ijk[2]);
  };
  std::vector<int> counts(v.cell_count(), 0);
  for (const ParticleSphere& p : particles) ++counts[cell_of(p)];
  std::vector<std::uint8_t> occupancy(v.cell_count());
  for (std::size_t c = 0; c < counts.size(); ++c)
    occupancy[c] = counts[c] == 0 ? cell::kEmpty : (counts[c] >= full_count ? cell::kFull : cell::kPartial);
  out.states.resize(v.cell_count());
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i) {
        const std::uint8_t own = occupancy[index(i, j, k)];
        bool inner = own != cell::kPartial;
        for (int dk = -1; dk <= 1 && inner; ++dk)
          for (int dj = -1; dj <= 1 && inner; ++dj)
            for (int di = -1; di <= 1 && inner; ++di) {
              const int x = i + di, y = j + dj, z = k + dk;
              const bool outside = x < 0 || y < 0 || z < 0 || x >= v.dims[0] || y >= v.dims[1] ||
                                   z >= v.dims[2];
              inner = (outside ? cell::kEmpty : occupancy[index(x, y, z)]) == own;
            }
        out.states[index(i, j, k)] = static_cast<std::uint8_t>(own | (inner ? cell::kInner : 0));
        if (inner) ++(own == cell::kFull ? out.inner_full_cells : out.inner_empty_cells);
      }
  v.states = out.states.data();
  for (const ParticleSphere& p : particles)
    if (!cell::is_inner(out.states[cell_of(p)])) out.boundary.push_back(p);
  return out;
}

}  // namespace voxspan::test
