// Classification on lattices with hand-counted answers: a solid block in air, a lone droplet.
#include <gtest/gtest.h>

#include <set>

#include "tests/sim_adapter/particle_sets.h"
#include "voxspan/classify.h"

namespace voxspan {
namespace {

using test::Point;

ClassifyOptions lattice_options() {
  ClassifyOptions o;
  o.particle_spacing = 1.0;  // cells of 2 spacings hold 8 particles at rest: full count 8
  return o;
}

// The lattice sorted into the grid, classified from its CSR offsets.
Classification classify_sorted(const std::vector<Point>& pts, const GridGeometry& g,
                               const ClassifyOptions& o = lattice_options()) {
  const test::SortedGrid s = test::sort_into(g, pts);
  return classify(ParticleView::aos(&s.sorted[0].x, s.sorted.size(), sizeof(Point)),
                  GridView::offsets(g, s.offsets.data()), o);
}

int chebyshev_distance_to_block(int i, int j, int k, int lo, int hi) {
  auto d = [&](int v) { return v < lo ? lo - v : v > hi ? v - hi : 0; };
  return std::max({d(i), d(j), d(k)});
}

// 16^3 particles of spacing 1 filling cells 2..9 of a 12^3 grid of cells of size 2.
TEST(ClassifyLattice, SolidBlockInAir) {
  std::vector<Point> pts;
  test::add_lattice(pts, {4, 4, 4}, {16, 16, 16}, 1.0);
  const GridGeometry g = test::cube_grid(2.0, 12);
  const Classification c = classify_sorted(pts, g);

  EXPECT_EQ(c.counts.full_count, 8);
  EXPECT_EQ(c.counts.cells, 1728u);
  EXPECT_EQ(c.counts.cells_full, 512u);        // 8^3 block cells
  EXPECT_EQ(c.counts.cells_inner_full, 216u);  // 6^3 cells away from the block's faces
  EXPECT_EQ(c.counts.cells_partial, 0u);
  EXPECT_EQ(c.counts.cells_empty, 1216u);
  EXPECT_EQ(c.counts.cells_inner_empty, 728u);  // all but the 10^3 cells touching the block
  EXPECT_EQ(c.counts.boundary, (512u - 216u) * 8u);
  EXPECT_EQ(c.counts.dropped_nonfinite, 0u);
  EXPECT_EQ(c.counts.not_in_grid, 0u);

  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) {
        const int d = chebyshev_distance_to_block(i, j, k, 2, 9);
        const std::uint8_t expected =
            d == 0
                ? (chebyshev_distance_to_block(i, j, k, 3, 8) == 0 ? cell::kInnerFull : cell::kFull)
            : d == 1 ? cell::kEmpty
                     : cell::kInnerEmpty;
        ASSERT_EQ(c.states[g.linear(i, j, k)], expected) << "cell " << i << " " << j << " " << k;
      }

  // Every particle within one cell (2 units) of the block's surface is a boundary particle,
  // and no other is.
  std::set<std::array<float, 3>> boundary;
  for (const ParticleSphere& p : c.boundary) {
    boundary.insert({p.x, p.y, p.z});
    EXPECT_EQ(p.radius, 1.0f);
  }
  EXPECT_EQ(boundary.size(), c.boundary.size());
  for (const Point& p : pts) {
    const float depth = std::min({p.x - 4, 20 - p.x, p.y - 4, 20 - p.y, p.z - 4, 20 - p.z});
    EXPECT_EQ(boundary.count({p.x, p.y, p.z}) == 1, depth <= 2.0f)
        << p.x << " " << p.y << " " << p.z;
  }
}

// 27 particles around a cell corner: one full cell with partial neighbours, all boundary.
TEST(ClassifyLattice, LoneDropletIsAllBoundary) {
  std::vector<Point> pts;
  test::add_lattice(pts, {10, 10, 10}, {3, 3, 3}, 1.0);
  const GridGeometry g = test::cube_grid(2.0, 12);
  const Classification c = classify_sorted(pts, g);

  EXPECT_EQ(c.counts.boundary, 27u);
  EXPECT_EQ(c.counts.cells_full, 1u);  // cell (5,5,5) holds 2x2x2 particles
  EXPECT_EQ(c.counts.cells_inner_full, 0u);
  EXPECT_EQ(c.counts.cells_partial, 7u);               // the rest of the droplet's 2x2x2 cells
  EXPECT_EQ(c.counts.cells_inner_empty, 1728u - 64u);  // all but cells 4..7 per axis
  EXPECT_EQ(c.states[g.linear(5, 5, 5)], cell::kFull);
  EXPECT_EQ(c.states[g.linear(6, 6, 6)], cell::kPartial);
  EXPECT_EQ(c.states[g.linear(4, 4, 4)], cell::kEmpty);
  EXPECT_EQ(c.states[g.linear(3, 4, 4)], cell::kInnerEmpty);
}

TEST(ClassifyLattice, SingleParticle) {
  const double p[3] = {5.0, 5.0, 5.0};
  const Classification c =
      classify(ParticleView::aos(p, 1).with_radius(0.25),
               GridView::geometry_only(test::cube_grid(2.0, 5)), lattice_options());
  ASSERT_EQ(c.boundary.size(), 1u);
  EXPECT_EQ(c.boundary[0].x, 5.0f);
  EXPECT_EQ(c.boundary[0].radius, 0.25f);
  EXPECT_EQ(c.counts.cells_partial, 1u);
  EXPECT_EQ(c.counts.cells_inner_empty, 125u - 27u);
}

// A full grid: the cells on the grid's faces touch the outside air, so only the core is inner.
TEST(ClassifyLattice, OutsideTheGridIsAir) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {8, 8, 8}, 1.0);
  const Classification c = classify_sorted(pts, test::cube_grid(2.0, 4));
  EXPECT_EQ(c.counts.cells_full, 64u);
  EXPECT_EQ(c.counts.cells_inner_full, 8u);
  EXPECT_EQ(c.counts.boundary, 56u * 8u);
}

TEST(ClassifyLattice, ExplicitFullCountWins) {
  std::vector<Point> pts;
  test::add_lattice(pts, {4, 4, 4}, {16, 16, 16}, 1.0);
  ClassifyOptions o = lattice_options();
  o.full_count = 9;  // more than a cell holds: nothing is full
  const Classification c = classify_sorted(pts, test::cube_grid(2.0, 12), o);
  EXPECT_EQ(c.counts.cells_full, 0u);
  EXPECT_EQ(c.counts.cells_partial, 512u);
  EXPECT_EQ(c.counts.boundary, pts.size());
}

TEST(ClassifyCells, FullCountFromSpacing) {
  ClassifyOptions o;
  o.particle_spacing = 1.0;
  EXPECT_EQ(full_count_for(o, 2.0), 8);
  // Cells of 2.4 spacings hold 2 or 3 lattice planes per axis: at least 8 particles.
  EXPECT_EQ(full_count_for(o, 2.4), 8);
  EXPECT_EQ(full_count_for(o, 3.0), 27);
  o.full_fraction = 0.5;
  EXPECT_EQ(full_count_for(o, 2.0), 4);
  o.full_count = 5;
  EXPECT_EQ(full_count_for(o, 2.0), 5);
}

TEST(ClassifyCells, FromCounts) {
  GridGeometry g = test::cube_grid(1.0, 3);
  std::vector<std::uint32_t> counts(27, 5);
  std::vector<std::uint8_t> states(27);
  classify_cells(g, counts, 5, states);
  EXPECT_EQ(states[13], cell::kInnerFull);  // the centre: all 26 neighbours full
  EXPECT_EQ(states[0], cell::kFull);        // a corner touches the outside air
  counts[0] = 4;
  classify_cells(g, counts, 5, states);
  EXPECT_EQ(states[13], cell::kFull);
  EXPECT_EQ(states[0], cell::kPartial);
}

}  // namespace
}  // namespace voxspan
