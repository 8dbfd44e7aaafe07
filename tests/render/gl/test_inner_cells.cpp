// Skipping inner cells ([ZD15] sec. 3.1, 4.3): the dam break voxelized from its boundary
// particles plus the cell states (inner-empty skipped, inner-full counted as inside) gives the
// spans of the run with every particle, within one layer, when gap bridging is at least the
// particle spacing (so the tiny gaps between touching spheres inside the fluid close in both).
#include "render/reference/exact_spans.h"
#include "tests/render/gl/render_fixture.h"
#include "tools/scenes/scene_cell_states.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/span_compare.h"

namespace voxspan {
namespace {

struct DamBreakRuns {
  test::Particles all;
  test::TestCells cells;
  Camera camera;
  VoxelizeOptions options;
};

DamBreakRuns dam_break_runs(double t) {
  test::DamBreak shape;
  shape.spacing = 0.01;
  shape.radius = 0.01;
  DamBreakRuns r;
  r.all = test::dam_break(shape, t);
  // Cells of two spacings hold 8 lattice particles when full.
  r.cells = test::classify_for_test(r.all, 2 * shape.spacing, 8);
  r.camera = test::frame_scene(r.all, {0.4, -0.5, -1}, 192, 108);
  r.options.grid.alpha_degrees = 2;
  r.options.gap_bridging = shape.spacing;
  return r;
}

TEST(InnerCells, SkippingChangesNoSpanByMoreThanOneLayer) {
  for (double t : {0.0, 0.15, 0.3}) {
    SCOPED_TRACE(t);
    const DamBreakRuns r = dam_break_runs(t);
    ASSERT_GT(r.cells.inner_full_cells, 0);
    ASSERT_LT(r.cells.boundary.size(), r.all.size() * 3 / 4) << "too few particles left out";
    const SpanImage every = test::voxelize(r.camera, r.all, r.options);
    // Same frame: the boundary particles span the same depth range.
    const SpanImage skipped = test::voxelize(r.camera, r.cells.boundary, r.options, r.cells.view);
    ASSERT_EQ(skipped.grid.layers(), every.grid.layers());
    const test::SpanComparison cmp = test::compare_spans(skipped, every, 1.0);
    std::printf("t=%.2f: %zu of %zu particles voxelized: %s\n", t, r.cells.boundary.size(),
                r.all.size(), cmp.summary().c_str());
    EXPECT_EQ(cmp.count_match(), 1.0)
        << cmp.summary() << test::describe_mismatches(skipped, every, 4);
    EXPECT_EQ(cmp.boundary_match(), 1.0) << cmp.summary();
  }
}

TEST(InnerCells, WithoutTheCellStatesTheBoundaryShellIsHollow) {
  // The check above can fail: boundary particles alone leave the inside of the fluid empty.
  const DamBreakRuns r = dam_break_runs(0.0);
  VoxelizeOptions o = r.options;
  const SpanImage every = test::voxelize(r.camera, r.all, o);
  o.use_cell_states = false;
  const SpanImage hollow = test::voxelize(r.camera, r.cells.boundary, o, r.cells.view);
  EXPECT_LT(test::compare_spans(hollow, every).count_match(), 0.9);
}

TEST(InnerCells, MatchTheReferenceWithTheSameCells) {
  const DamBreakRuns r = dam_break_runs(0.15);
  const SpanImage gpu = test::voxelize(r.camera, r.cells.boundary, r.options, r.cells.view);
  const SpanImage ref =
      exact_spans(gpu.grid, r.cells.boundary, r.cells.view, {r.options.gap_bridging, 0});
  const test::SpanComparison cmp = test::compare_spans(gpu, ref);
  EXPECT_GE(cmp.count_match(), 0.995) << cmp.summary();
  EXPECT_GE(cmp.boundary_match(), 0.995) << cmp.summary();
  EXPECT_LE(cmp.inside_sum_error(), 0.01) << cmp.summary();
}

}  // namespace
}  // namespace voxspan
