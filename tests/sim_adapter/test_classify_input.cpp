// Bad and unusual input: NaN/inf positions, grids that do not match the particles, zero
// particles, ghosts, attributes, far-flung particles with no grid.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/sim_adapter/particle_sets.h"
#include "voxspan/classify.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

using test::Point;

ClassifyOptions options() {
  ClassifyOptions o;
  o.particle_spacing = 1.0;
  return o;
}

std::string error_of(const ParticleView& v, const GridView& g, const ClassifyOptions& o) {
  try {
    classify(v, g, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ClassifyInput, NonFinitePositionsAreCountedAndLeftOut) {
  std::vector<Point> pts;
  test::add_lattice(pts, {2, 2, 2}, {4, 4, 4}, 1.0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  pts[3].x = nan;
  pts[10].y = inf;
  pts[20].z = -inf;
  const GridGeometry g = test::cube_grid(2.0, 5);
  test::SortedGrid s = test::sort_into(g, pts);  // the NaN particles land in clamped cells
  for (auto grid :
       {GridView::offsets(g, s.offsets.data()).with_order(s.order.data()),
        GridView::cell_index(g, s.cells.data()), GridView::geometry_only(g), GridView()}) {
    const Classification c =
        classify(ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point)), grid, options());
    EXPECT_EQ(c.counts.dropped_nonfinite, 3u);
    EXPECT_EQ(c.counts.boundary, pts.size() - 3);
    for (const ParticleSphere& p : c.boundary)
      EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  }
}

TEST(ClassifyInput, NonFiniteRadiusIsLeftOut) {
  std::vector<Point> pts;
  test::add_lattice(pts, {2, 2, 2}, {2, 2, 2}, 1.0);
  std::vector<double> radii(pts.size(), 0.5);
  radii[1] = std::numeric_limits<double>::quiet_NaN();
  radii[2] = -1;
  const Classification c =
      classify(ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point)).with_radii(radii.data()),
               GridView::geometry_only(test::cube_grid(2.0, 4)), options());
  EXPECT_EQ(c.counts.dropped_nonfinite, 2u);
  EXPECT_EQ(c.boundary.size(), pts.size() - 2);
  for (const ParticleSphere& p : c.boundary) EXPECT_EQ(p.radius, 0.5f);
}

TEST(ClassifyInput, ValidationNamesTheParticleAndTheCell) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {6, 6, 6}, 1.0);
  const GridGeometry g = test::cube_grid(2.0, 3);
  test::SortedGrid s = test::sort_into(g, pts);
  // Move one sorted particle far from the cell the grid lists it in.
  const std::size_t moved = s.offsets[g.linear(0, 0, 0)];  // first particle of cell (0,0,0)
  s.sorted[moved] = {5.5f, 5.5f, 5.5f};
  const auto view = ParticleView::aos(&s.sorted[0].x, s.sorted.size(), sizeof(Point));
  const auto grid = GridView::offsets(g, s.offsets.data());
  ClassifyOptions o = options();
  EXPECT_EQ(error_of(view, grid, o), "");  // without validation the mismatch goes unseen
  o.validate = true;
  const std::string e = error_of(view, grid, o);
  EXPECT_NE(e.find("particle " + std::to_string(moved) + " at (5.5, 5.5, 5.5)"), std::string::npos)
      << e;
  EXPECT_NE(e.find("lies in cell (2, 2, 2)"), std::string::npos) << e;
  EXPECT_NE(e.find("lists it in cell (0, 0, 0)"), std::string::npos) << e;

  // The same for a per-particle cell index that lies.
  std::vector<std::uint32_t> cells = s.cells;
  cells[7] = std::uint32_t(g.linear(1, 2, 0));
  const std::string e2 = error_of(ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point)),
                                  GridView::cell_index(g, cells.data()), o);
  EXPECT_NE(e2.find("particle 7 "), std::string::npos) << e2;
  EXPECT_NE(e2.find("cell (1, 2, 0)"), std::string::npos) << e2;
}

TEST(ClassifyInput, ValidationFindsMissingAndDuplicatedParticles) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {4, 4, 4}, 1.0);
  const GridGeometry g = test::cube_grid(2.0, 2);
  test::SortedGrid s = test::sort_into(g, pts);
  ClassifyOptions o = options();
  o.validate = true;
  std::vector<std::uint32_t> order = s.order;
  order[1] = order[0];  // particle order[1] vanishes, order[0] is listed twice
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  EXPECT_NE(error_of(view, GridView::offsets(g, s.offsets.data()).with_order(order.data()), o)
                .find("listed twice"),
            std::string::npos);

  // Particles in no cell: counted without validation, an error with it.
  std::vector<std::uint32_t> offsets = s.offsets;
  offsets.back() -= 2;
  o.validate = false;
  const Classification c =
      classify(view, GridView::offsets(g, offsets.data()).with_order(s.order.data()), o);
  EXPECT_EQ(c.counts.not_in_grid, 2u);
  o.validate = true;
  EXPECT_NE(error_of(view, GridView::offsets(g, offsets.data()).with_order(s.order.data()), o)
                .find("is in no cell of the grid"),
            std::string::npos);
}

// A grid of more cells than 32 bits count (a cell size far below the domain) is refused,
// named, before anything is allocated for it.
TEST(ClassifyInput, AGridOfMoreThan2To32CellsIsRefused) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {2, 2, 2}, 1.0);
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  const GridView huge =
      GridView::geometry_only(GridGeometry{{0, 0, 0}, 1e-5, {100000, 100000, 100000}});
  EXPECT_NE(error_of(view, huge, options())
                .find("grid of 100000 x 100000 x 100000 cells (1e+15) has more than 2^32 cells"),
            std::string::npos)
      << error_of(view, huge, options());
}

TEST(ClassifyInput, RangesOutOfBoundsAreErrorsAlways) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {4, 4, 4}, 1.0);
  const GridGeometry g = test::cube_grid(2.0, 2);
  test::SortedGrid s = test::sort_into(g, pts);
  const auto view = ParticleView::aos(&s.sorted[0].x, s.sorted.size(), sizeof(Point));
  std::vector<std::uint32_t> offsets = s.offsets;
  offsets.back() += 5;
  EXPECT_NE(error_of(view, GridView::offsets(g, offsets.data()), options())
                .find("grid cell (1, 1, 1) lists particles [56, 69), outside the 64 particles"),
            std::string::npos);
  std::vector<std::uint32_t> backwards = s.offsets;
  backwards[1] = backwards[2] + 1;  // cell 0 ends after cell 1's end: cell 1 runs backwards
  EXPECT_NE(error_of(view, GridView::offsets(g, backwards.data()), options())
                .find("its range ends before it begins (offsets must not decrease)"),
            std::string::npos);
  std::vector<std::uint32_t> order = s.order;
  order[3] = 1000;
  EXPECT_NE(
      error_of(view, GridView::offsets(g, s.offsets.data()).with_order(order.data()), options())
          .find("is particle 1000, not one of the 64"),
      std::string::npos);
  std::vector<std::int32_t> cells(s.cells.begin(), s.cells.end());
  cells[5] = -1;
  EXPECT_NE(error_of(view, GridView::cell_index(g, cells.data()), options())
                .find("cell index of particle 5 is -1"),
            std::string::npos);
  GridGeometry bad = g;
  bad.cell_size = 0;
  EXPECT_NE(error_of(view, GridView::geometry_only(bad), options()).find("invalid grid geometry"),
            std::string::npos);
}

TEST(ClassifyInput, ZeroParticlesIsAValidStep) {
  const GridGeometry g = test::cube_grid(2.0, 3);
  std::vector<std::uint32_t> offsets(g.cell_count() + 1, 0);
  for (auto grid : {GridView::offsets(g, offsets.data()), GridView::geometry_only(g), GridView()}) {
    const Classification c = classify(ParticleView(), grid, options());
    EXPECT_EQ(c.boundary.size(), 0u);
    EXPECT_EQ(c.counts.particles, 0u);
    EXPECT_EQ(c.counts.cells_inner_empty, c.counts.cells);
  }
}

TEST(ClassifyInput, GhostsCountButAreNotCompactedWhenAsked) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {2, 2, 4}, 1.0);  // two cells of 8, owned = first 8
  const GridGeometry g = test::cube_grid(2.0, 3);
  ClassifyOptions o = options();
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point)).with_owned(8);
  Classification c = classify(view, GridView::geometry_only(g), o);
  EXPECT_EQ(c.counts.owned, 8u);
  EXPECT_EQ(c.counts.cells_full, 2u);
  EXPECT_EQ(c.boundary.size(), 16u);
  o.include_ghosts = false;
  c = classify(view, GridView::geometry_only(g), o);
  EXPECT_EQ(c.counts.cells_full, 2u);  // ghosts still fill their cell
  EXPECT_EQ(c.boundary.size(), 8u);
  for (const ParticleSphere& p : c.boundary) EXPECT_LT(p.z, 2.0f);
}

TEST(ClassifyInput, AttributesFollowTheBoundaryOrder) {
  const std::vector<Point> pts = test::noisy_scene(3);
  std::vector<double> density;
  std::vector<float> velocity;
  for (const Point& p : pts) {
    density.push_back(1000.0 + p.x);
    velocity.insert(velocity.end(), {p.y, 2 * p.z, -p.x});
  }
  ClassifyOptions o = options();
  o.attributes = {"velocity", "density"};
  const Classification c = classify(ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point))
                                        .with_scalar("density", density.data())
                                        .with_vector("velocity", velocity.data()),
                                    GridView::geometry_only(test::cube_grid(2.0, 15)), o);
  ASSERT_EQ(c.attributes.size(), 2u);
  EXPECT_EQ(c.attributes[0].name, "velocity");
  EXPECT_EQ(c.attributes[0].components, 3);
  ASSERT_EQ(c.attributes[0].values.size(), 3 * c.boundary.size());
  ASSERT_EQ(c.attributes[1].values.size(), c.boundary.size());
  for (std::size_t k = 0; k < c.boundary.size(); ++k) {
    const ParticleSphere& p = c.boundary[k];
    EXPECT_EQ(c.attributes[1].values[k], float(1000.0 + p.x));
    EXPECT_EQ(c.attributes[0].values[3 * k + 0], p.y);
    EXPECT_EQ(c.attributes[0].values[3 * k + 1], 2 * p.z);
    EXPECT_EQ(c.attributes[0].values[3 * k + 2], -p.x);
  }

  o.attributes = {"pressure"};
  const std::string e = error_of(ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point))
                                     .with_scalar("density", density.data()),
                                 GridView(), o);
  EXPECT_NE(e.find("attribute 'pressure' was asked for but the solver passes no attribute of that "
                   "name (it passes: density)"),
            std::string::npos)
      << e;
  o.attributes = {"densty"};  // a typo is named with its near miss
  const std::string typo = error_of(ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point))
                                        .with_scalar("density", density.data()),
                                    GridView(), o);
  EXPECT_NE(typo.find("(did you mean \"density\"? it passes: density)"), std::string::npos) << typo;
}

TEST(ClassifyInput, TooManyAttributesIsAnErrorNotACrash) {
  std::vector<Point> pts(1, Point{1, 1, 1});
  std::vector<float> v(1, 0.f);
  auto view = ParticleView::aos(&pts[0].x, 1, sizeof(Point));
  for (int k = 0; k <= ParticleView::kMaxAttributes; ++k)
    view.with_scalar(k == ParticleView::kMaxAttributes ? "the_extra_one" : "a", v.data());
  EXPECT_NE(error_of(view, GridView(), options()).find("'the_extra_one'"), std::string::npos);
}

// What would silently pick one of two values, or none: each an error naming it.
TEST(ClassifyInput, TwinAndEmptyAttributeNamesAndBadRadiiAreNamed) {
  std::vector<Point> pts(1, Point{1, 1, 1});
  std::vector<float> v(3, 0.f);
  const auto view = [&] { return ParticleView::aos(&pts[0].x, 1, sizeof(Point)); };
  EXPECT_NE(error_of(view().with_scalar("velocity", v.data()).with_vector("velocity", v.data()),
                     GridView(), options())
                .find("two attributes named 'velocity' (1 and 3 components)"),
            std::string::npos);
  EXPECT_NE(error_of(view().with_scalar("", v.data()), GridView(), options()).find("no name"),
            std::string::npos);
  for (double r : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_NE(error_of(view().with_radius(r), GridView(), options())
                  .find("is not a positive finite number"),
              std::string::npos)
        << r;
}

TEST(ClassifyInput, FarFlungParticlesKeepTheBuiltGridBounded) {
  std::vector<Point> pts{{0, 0, 0}, {1, 1, 1}, {1e6f, 1e6f, 1e6f}};
  ClassifyOptions o = options();
  o.max_built_cells = 1 << 20;
  const Classification c =
      classify(ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point)), GridView(), o);
  EXPECT_LE(c.geometry.cell_count(), o.max_built_cells);
  EXPECT_GT(c.geometry.cell_size, 2.0);
  EXPECT_EQ(c.boundary.size(), 3u);
}

TEST(ClassifyInput, MissingSpacingAndRadiusAreNamed) {
  std::vector<Point> pts(1, Point{1, 1, 1});
  ClassifyOptions o;
  EXPECT_NE(error_of(ParticleView::aos(&pts[0].x, 1, sizeof(Point)), GridView(), o)
                .find("no particle radius"),
            std::string::npos);
  EXPECT_NE(error_of(ParticleView::aos(&pts[0].x, 1, sizeof(Point)).with_radius(1), GridView(), o)
                .find("cell size is unknown"),
            std::string::npos);
}

}  // namespace
}  // namespace voxspan
