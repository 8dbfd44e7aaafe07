// The exact CPU reference: analytic spans of one sphere, the union of overlapping and touching
// spheres, gap bridging, the span cap with exact inside length, inner-full cells counted as
// inside, and the cell march it uses.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/cell_march.h"
#include "render/reference/exact_spans.h"
#include "tools/scenes/scenes.h"

namespace voxspan {
namespace {

// A 3x1 image looking down -z; the centre pixel's ray is the z axis.
PerspectiveGrid grid(double near = 1, double far = 20) {
  return PerspectiveGrid::over(test::look_at({0, 0, 0}, {0, 0, -1}, 3, 1, 1), near, far,
                               GridOptions{});
}

std::vector<Span> centre_spans(const SpanImage& image) {
  const auto s = image.spans_at(1, 0);
  return {s.begin(), s.end()};
}

TEST(Reference, OneSphereIsItsAnalyticChord) {
  const std::vector<ParticleSphere> p = {{0, 0, -5, 1}};
  const SpanImage image = exact_spans(grid(), p, {}, {});
  const auto s = centre_spans(image);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_FLOAT_EQ(s[0].entry, 4.0f);
  EXPECT_FLOAT_EQ(s[0].exit, 6.0f);
  EXPECT_FLOAT_EQ(image.pixel(1, 0).inside, 2.0f);
}

TEST(Reference, UnionOfOverlappingAndTouchingSpheres) {
  const std::vector<ParticleSphere> p = {
      {0, 0, -5, 1}, {0, 0, -6.5f, 1}, {0, 0, -9.5f, 1}, {0, 0, -11.5f, 1}, {0, 0, -15, 1}};
  const auto s = centre_spans(exact_spans(grid(), p, {}, {}));
  ASSERT_EQ(s.size(), 3u);  // 4..7.5, 8.5..12.5 (touching at 10.5), 14..16
  EXPECT_FLOAT_EQ(s[0].exit, 7.5f);
  EXPECT_FLOAT_EQ(s[1].entry, 8.5f);
  EXPECT_FLOAT_EQ(s[1].exit, 12.5f);
  EXPECT_FLOAT_EQ(s[2].entry, 14.0f);
}

TEST(Reference, GapsShorterThanGClose) {
  const std::vector<ParticleSphere> p = {{0, 0, -5, 1}, {0, 0, -8, 1}, {0, 0, -12, 1}};
  // Gaps of 1 and 2 along the ray (the centre ray has ray_scale 1).
  EXPECT_EQ(centre_spans(exact_spans(grid(), p, {}, {0.9, 0})).size(), 3u);
  EXPECT_EQ(centre_spans(exact_spans(grid(), p, {}, {1.1, 0})).size(), 2u);
  EXPECT_EQ(centre_spans(exact_spans(grid(), p, {}, {2.1, 0})).size(), 1u);
  // Bridged gaps count as inside.
  EXPECT_FLOAT_EQ(exact_spans(grid(), p, {}, {2.1, 0}).pixel(1, 0).inside, 9.0f);
}

TEST(Reference, CapExtendsTheLastSpanAndKeepsInsideExact) {
  std::vector<ParticleSphere> p;
  for (int i = 0; i < 5; ++i) p.push_back({0, 0, -3.0f - 3 * i, 1});  // spans 2..4, 5..7, ...
  const SpanImage image = exact_spans(grid(), p, {}, {0, 2});
  const PixelSpans& px = image.pixel(1, 0);
  EXPECT_EQ(px.count, 2u);
  EXPECT_EQ(px.total, 5u);
  EXPECT_FLOAT_EQ(px.inside, 10.0f);  // five chords of 2, although the stored spans cover 14
  const auto s = centre_spans(image);
  EXPECT_FLOAT_EQ(s[0].entry, 2.0f);
  EXPECT_FLOAT_EQ(s[0].exit, 4.0f);
  EXPECT_FLOAT_EQ(s[1].entry, 5.0f);
  EXPECT_FLOAT_EQ(s[1].exit, 16.0f);
  // The extended span 5..16 holds the gaps 7..8, 10..11 and 13..14.
  EXPECT_NEAR(image.capped_gap_length(1, 0), 3.0, 1e-5);
  EXPECT_EQ(image.capped_pixels(), 3);  // the narrow view puts all three pixels in the spheres
  EXPECT_EQ(image.total_spans(), 15);
}

TEST(Reference, SpansAreClippedToTheNearPlane) {
  const std::vector<ParticleSphere> p = {{0, 0, -1.5f, 1}};
  const auto s = centre_spans(exact_spans(grid(1, 20), p, {}, {}));
  ASSERT_EQ(s.size(), 1u);
  EXPECT_FLOAT_EQ(s[0].entry, 1.0f);
  EXPECT_FLOAT_EQ(s[0].exit, 2.5f);
}

struct Cells {
  std::vector<std::uint8_t> states;
  CellStatesView view;
};

// A 4x4x4 grid of unit cells from (-2, -2, -12); the inner 2x2x2 block inner-full.
Cells block_cells() {
  Cells c;
  c.states.assign(64, cell::kFull);
  for (int k = 1; k < 3; ++k)
    for (int j = 1; j < 3; ++j)
      for (int i = 1; i < 3; ++i)
        c.states[static_cast<std::size_t>(i + 4 * (j + 4 * k))] = cell::kInnerFull;
  c.view.origin = {-2, -2, -12};
  c.view.cell_size = 1;
  c.view.dims = {4, 4, 4};
  c.view.states = c.states.data();
  return c;
}

TEST(Reference, InnerFullCellsCountAsInside) {
  const Cells c = block_cells();
  // The centre ray (x = y = 0) runs along cell boundaries through the inner block, which spans
  // z = -11 .. -9: depth 9 .. 11.
  const auto s = centre_spans(exact_spans(grid(), {}, c.view, {}));
  ASSERT_EQ(s.size(), 1u);
  EXPECT_FLOAT_EQ(s[0].entry, 9.0f);
  EXPECT_FLOAT_EQ(s[0].exit, 11.0f);
}

TEST(CellMarch, VisitsConsecutiveCellsCoveringTheGrid) {
  const Cells c = block_cells();
  const glm::dvec3 eye(0.3, -0.2, 0), ray(0.05, 0.02, -1);
  double last = -1, first = -1;
  int visits = 0;
  march_cells(c.view, eye, ray, 0, 100, [&](std::uint8_t, double z_in, double z_out) {
    if (first < 0) first = z_in;
    if (last >= 0) {
      EXPECT_DOUBLE_EQ(z_in, last);
    }
    EXPECT_GT(z_out, z_in);
    last = z_out;
    ++visits;
  });
  EXPECT_NEAR(first, 8.0, 1e-12);  // the grid's box spans z = -12 .. -8
  EXPECT_NEAR(last, 12.0, 1e-12);
  EXPECT_GE(visits, 4);
}

}  // namespace
}  // namespace voxspan
