// The same scene through every supported particle and grid layout gives the same cell states,
// counts and boundary particles.
#include <gtest/gtest.h>

#include "tests/sim_adapter/particle_sets.h"
#include "voxspan/classify.h"

namespace voxspan {
namespace {

using test::Point;

struct Reference {
  std::vector<Point> pts = test::noisy_scene(7);
  GridGeometry g = test::cube_grid(2.0, 15);
  test::SortedGrid s = test::sort_into(g, pts);
  ClassifyOptions options;
  Classification expected;

  Reference() {
    options.particle_spacing = 1.0;
    expected = classify(ParticleView::aos(&s.sorted[0].x, s.sorted.size(), sizeof(Point)),
                        GridView::offsets(g, s.offsets.data()), options);
  }
};

const Reference& reference() {
  static const Reference r;
  return r;
}

void expect_same(const Classification& c, bool same_order = true) {
  const Classification& e = reference().expected;
  EXPECT_EQ(c.states, e.states);
  EXPECT_EQ(c.counts.boundary, e.counts.boundary);
  EXPECT_EQ(c.counts.cells_inner_full, e.counts.cells_inner_full);
  EXPECT_EQ(c.counts.cells_inner_empty, e.counts.cells_inner_empty);
  EXPECT_EQ(c.counts.cells_partial, e.counts.cells_partial);
  EXPECT_EQ(test::sorted_spheres(c), test::sorted_spheres(e));
  if (same_order) {
    ASSERT_EQ(c.boundary.size(), e.boundary.size());
    for (std::size_t k = 0; k < c.boundary.size(); ++k)
      ASSERT_EQ(c.boundary[k].x, e.boundary[k].x) << "boundary particle " << k;
  }
}

TEST(ClassifyLayouts, ReferenceSceneHasEveryKindOfCell) {
  const ClassifyCounts& c = reference().expected.counts;
  EXPECT_GT(c.cells_inner_full, 0u);
  EXPECT_GT(c.cells_full, c.cells_inner_full);
  EXPECT_GT(c.cells_partial, 0u);
  EXPECT_GT(c.cells_inner_empty, 0u);
  EXPECT_GT(c.boundary, 0u);
  EXPECT_LT(c.boundary, reference().pts.size());
}

TEST(ClassifyLayouts, SoaFloatAndDouble) {
  const Reference& r = reference();
  std::vector<float> xf, yf, zf;
  std::vector<double> xd, yd, zd;
  for (const Point& p : r.s.sorted) {
    xf.push_back(p.x), yf.push_back(p.y), zf.push_back(p.z);
    xd.push_back(p.x), yd.push_back(p.y), zd.push_back(p.z);
  }
  const auto grid = GridView::offsets(r.g, r.s.offsets.data());
  expect_same(
      classify(ParticleView::soa(xf.data(), yf.data(), zf.data(), xf.size()), grid, r.options));
  expect_same(
      classify(ParticleView::soa(xd.data(), yd.data(), zd.data(), xd.size()), grid, r.options));
}

TEST(ClassifyLayouts, AosDoubleWithStride) {
  const Reference& r = reference();
  struct Particle {
    double velocity[3];
    double position[3];
    int id;
  };
  std::vector<Particle> particles;
  for (const Point& p : r.s.sorted) particles.push_back({{1, 2, 3}, {p.x, p.y, p.z}, 0});
  expect_same(classify(ParticleView::aos(particles[0].position, particles.size(), sizeof(Particle)),
                       GridView::offsets(r.g, r.s.offsets.data()), r.options));
}

TEST(ClassifyLayouts, BeginEndSigned64) {
  const Reference& r = reference();
  std::vector<std::int64_t> begin, end;
  for (std::size_t c = 0; c < r.g.cell_count(); ++c) {
    begin.push_back(r.s.offsets[c]);
    end.push_back(r.s.offsets[c + 1]);
  }
  expect_same(classify(ParticleView::aos(&r.s.sorted[0].x, r.s.sorted.size(), sizeof(Point)),
                       GridView::begin_end(r.g, begin.data(), end.data()), r.options));
}

TEST(ClassifyLayouts, UnsortedParticlesWithOrder) {
  const Reference& r = reference();
  expect_same(classify(ParticleView::aos(&r.pts[0].x, r.pts.size(), sizeof(Point)),
                       GridView::offsets(r.g, r.s.offsets.data()).with_order(r.s.order.data()),
                       r.options));
}

TEST(ClassifyLayouts, FortranOneBased) {
  const Reference& r = reference();
  std::vector<std::int32_t> offsets(r.s.offsets.begin(), r.s.offsets.end()), order;
  for (std::int32_t& o : offsets) ++o;
  for (std::uint32_t i : r.s.order) order.push_back(std::int32_t(i) + 1);
  expect_same(
      classify(ParticleView::aos(&r.pts[0].x, r.pts.size(), sizeof(Point)),
               GridView::offsets(r.g, offsets.data()).with_order(order.data()).with_index_base(1),
               r.options));
}

TEST(ClassifyLayouts, PerParticleCellIndex) {
  const Reference& r = reference();
  // The unsorted particles with their cells: the classifier sorts them itself, keeping
  // ascending index order within a cell, the same order sort_into() gives.
  expect_same(classify(ParticleView::aos(&r.pts[0].x, r.pts.size(), sizeof(Point)),
                       GridView::cell_index(r.g, r.s.cells.data()), r.options));
  std::vector<std::uint64_t> cells(r.s.cells.begin(), r.s.cells.end());
  const Classification c = classify(ParticleView::aos(&r.pts[0].x, r.pts.size(), sizeof(Point)),
                                    GridView::cell_index(r.g, cells.data()), r.options);
  expect_same(c);
  EXPECT_TRUE(c.counts.grid_built);
}

TEST(ClassifyLayouts, GeometryOnly) {
  const Reference& r = reference();
  expect_same(classify(ParticleView::aos(&r.pts[0].x, r.pts.size(), sizeof(Point)),
                       GridView::geometry_only(r.g), r.options));
}

TEST(ClassifyLayouts, NoGridAtAll) {
  // The built grid's cells are aligned to multiples of the cell size from the particles'
  // bounds; with the reference grid at the origin the cells coincide, so the states agree
  // on the overlap and the boundary particles are the same.
  const Reference& r = reference();
  ClassifyOptions o = r.options;
  o.cell_size = 2.0;
  const Classification c =
      classify(ParticleView::aos(&r.pts[0].x, r.pts.size(), sizeof(Point)), GridView(), o);
  EXPECT_TRUE(c.counts.grid_built);
  EXPECT_EQ(c.geometry.cell_size, 2.0);
  EXPECT_EQ(test::sorted_spheres(c), test::sorted_spheres(r.expected));
  const GridGeometry& b = c.geometry;
  for (int k = 0; k < b.dims[2]; ++k)
    for (int j = 0; j < b.dims[1]; ++j)
      for (int i = 0; i < b.dims[0]; ++i) {
        const int gi = i + int(b.origin[0] / 2), gj = j + int(b.origin[1] / 2),
                  gk = k + int(b.origin[2] / 2);
        const std::uint8_t ref = r.expected.states[r.g.linear(gi, gj, gk)];
        // Cells on the built grid's faces see air beyond; the reference may see more cells.
        const bool face = i == 0 || j == 0 || k == 0 || i == b.dims[0] - 1 || j == b.dims[1] - 1 ||
                          k == b.dims[2] - 1;
        if (!face) ASSERT_EQ(c.states[b.linear(i, j, k)], ref);
        else ASSERT_EQ(cell::occupancy(c.states[b.linear(i, j, k)]), cell::occupancy(ref));
      }
}

TEST(ClassifyLayouts, DefaultCellSizeIsTwoSpacings) {
  const Reference& r = reference();
  const Classification c =
      classify(ParticleView::aos(&r.pts[0].x, r.pts.size(), sizeof(Point)), GridView(), r.options);
  EXPECT_EQ(c.geometry.cell_size, 2.0);
  EXPECT_EQ(c.counts.full_count, 8);
}

}  // namespace
}  // namespace voxspan
