#include "tools/scenes/scene_cell_states.h"

#include <algorithm>
#include <cmath>

#include "voxspan/classify.h"

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
  // A grid aligned with the origin, one cell of margin: the solver side's classifier sorts the
  // particles into it itself.
  GridGeometry g;
  g.cell_size = h;
  for (int a = 0; a < 3; ++a) {
    g.origin[a] = (std::floor(lo[a] / h) - 1) * h;
    g.dims[a] = static_cast<int>(std::floor((hi[a] - g.origin[a]) / h)) + 2;
  }
  ClassifyOptions options;
  options.particle_spacing = h / 2;
  options.full_count = full_count;
  const std::size_t stride = sizeof(ParticleSphere);
  const ParticleView view = ParticleView::aos(&particles[0].x, particles.size(), stride)
                                .with_radii(&particles[0].radius, stride);
  Classification c = classify(view, GridView::geometry_only(g), options);
  out.states = std::move(c.states);
  out.boundary = std::move(c.boundary);
  out.inner_full_cells = static_cast<std::int64_t>(c.counts.cells_inner_full);
  out.inner_empty_cells = static_cast<std::int64_t>(c.counts.cells_inner_empty);
  out.view = {g.origin, g.cell_size, g.dims, out.states.data()};
  return out;
}

}  // namespace voxspan::test
