// The fluid's spans cut at a backdrop's walls (render/backdrop.h), in place: every span kept ends
// before its pixel's wall, exactly the spans a copy-and-cut would keep, pixels the walls miss
// untouched (capped records included), a cut one's fluid length its kept spans', and
// reaches_past_walls says whether any pixel is cut.
#include <gtest/gtest.h>

#include <algorithm>

#include "render/backdrop.h"
#include "render/reference/exact_spans.h"
#include "tools/scenes/scenes.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

SpanImage cloud_spans() {
  const test::Particles p = test::random_cloud(400, {0, 0, 0}, {1, 1, 1}, 0.02, 0.1, 5);
  const Camera camera = test::frame_scene(p, {0.2, 0.3, -1}, 48, 32);
  return exact_spans(PerspectiveGrid::over(camera, 0.5, 5, GridOptions{}), p, {}, {0.01, 3});
}

// Walls at a depth that varies over the image, so that some pixels are cut and some are not.
Backdrop slanted_walls(const SpanImage& spans, float near, float far) {
  Backdrop b{spans.width(), spans.height(), {}, 1};
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x)
      b.pixels.push_back({0, 0, 0, near + (far - near) * float(x) / float(b.width - 1)});
  return b;
}

TEST(Backdrop, ClipAtWallsCutsInPlaceWhereTheWallsBegin) {
  const SpanImage before = cloud_spans();
  ASSERT_GT(before.spans.size(), 200u);
  float lo = 3e38f, hi = 0;
  for (const Span& s : before.spans) lo = std::min(lo, s.entry), hi = std::max(hi, s.exit);
  const Backdrop walls = slanted_walls(before, lo, hi);

  SpanImage after = before;
  ASSERT_TRUE(reaches_past_walls(after, walls));
  const std::int64_t cut = clip_at_walls(after, walls);
  EXPECT_GT(cut, 10);
  EXPECT_FALSE(reaches_past_walls(after, walls));

  std::int64_t changed = 0;
  for (int y = 0; y < before.height(); ++y)
    for (int x = 0; x < before.width(); ++x) {
      const float wall = walls.wall_depth(x, y);
      const auto in = before.spans_at(x, y), out = after.spans_at(x, y);
      std::size_t expected = 0;
      double length = 0;
      for (const Span& s : in) {
        if (s.entry >= wall) break;
        ASSERT_LT(expected, out.size()) << x << "," << y;
        EXPECT_EQ(out[expected].entry, s.entry);
        EXPECT_EQ(out[expected].exit, std::min(s.exit, wall));
        length += out[expected].exit - s.entry;
        ++expected;
      }
      EXPECT_EQ(out.size(), expected) << x << "," << y;
      const PixelSpans &a = before.pixel(x, y), &b = after.pixel(x, y);
      if (in.empty() || in.back().exit <= wall) {
        EXPECT_EQ(b.count, a.count);
        EXPECT_EQ(b.total, a.total);
        EXPECT_EQ(b.inside, a.inside);
      } else {
        ++changed;
        EXPECT_EQ(b.total, b.count);
        EXPECT_FLOAT_EQ(b.inside, float(length * before.grid.view().ray_scale(x, y)));
      }
    }
  EXPECT_EQ(changed, cut);
}

TEST(Backdrop, NoWallsCutNothing) {
  SpanImage spans = cloud_spans();
  const Backdrop none = slanted_walls(spans, Backdrop::kNoWall, Backdrop::kNoWall);
  EXPECT_FALSE(reaches_past_walls(spans, none));
  EXPECT_EQ(clip_at_walls(spans, none), 0);
  const Backdrop small{4, 4, std::vector<glm::vec4>(16), 1};
  EXPECT_THROW(clip_at_walls(spans, small), Error);
}

}  // namespace
}  // namespace voxspan
