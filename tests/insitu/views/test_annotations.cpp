// What a picture says of itself: the colour bar's title (the quantity, its `units`) and a view's
// `caption` with the step's numbers, through the runtime; the caption's pattern refused with
// its line when it names a field that does not exist.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>

#include "insitu/views/legend.h"

#include "insitu/config/caption.h"
#include "tests/support/view_tests.h"

namespace voxspan {
namespace {

constexpr double kSpacing = 0.05;
constexpr int kWidth = 320, kHeight = 180;

test::ParticleBlock block() {
  return {kSpacing, "speed", [](int, double x) { return x; }};
}

FloatImage picture(const std::string& keys) {
  return test::first_picture(
      test::one_view_config(
          "annotations", "name: p, kind: particles, width: " + std::to_string(kWidth) +
                             ", height: " + std::to_string(kHeight) + ", color_by: speed, " + keys),
      block());
}

// The box holding every pixel where a and b differ; empty (x0 > x1) when none does.
struct Box {
  int x0 = kWidth, y0 = kHeight, x1 = -1, y1 = -1;
};
Box differing(const FloatImage& a, const FloatImage& b) {
  Box box;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      if (a.at(x, y) != b.at(x, y)) {
        box.x0 = std::min(box.x0, x), box.x1 = std::max(box.x1, x);
        box.y0 = std::min(box.y0, y), box.y1 = std::max(box.y1, y);
      }
  return box;
}

TEST(Annotations, TheColourBarsTitleCarriesTheUnitsAboveTheBar) {
  const Box d = differing(picture("caption: '', units: m/s"), picture("caption: ''"));
  ASSERT_LE(d.x0, d.x1) << "the units changed nothing";
  // The title row: above the bar (its top at a tenth of the height) and its top value's label
  // (centred on the bar's top) with at least 4 blank rows between (3 read as one line), flush
  // with the bar's right edge.
  const int s = text_scale(kHeight), label_top = kHeight / 10 - 7 * s / 2 - s;
  EXPECT_LT(d.y1, label_top - 4 * s);
  EXPECT_GT(d.x0, kWidth / 2);
}

TEST(Annotations, TheCaptionIsDrawnAtTheTopLeftAndNowhereElse) {
  const FloatImage none = picture("caption: ''");
  for (const std::string keys : {"caption: 'step {step}, t = {time} s'", ""}) {  // "": default
    const Box d = differing(picture(keys), none);
    ASSERT_LE(d.x0, d.x1) << keys << ": the caption drew nothing";
    EXPECT_LT(d.x1, kWidth / 2) << keys;
    EXPECT_LT(d.y1, 16) << keys;
  }
}

// The colour bar's margins (what automatic framing keeps the fluid out of) cover every pixel
// that the bar and its longest values draw, at either edge, below the title's rows.
TEST(Annotations, TheColourBarsMarginsCoverTheBarAndItsValues) {
  for (const auto& [width, height] : {std::pair{320, 180}, std::pair{1920, 1080}})
    for (const BarSide side : {BarSide::right, BarSide::left}) {
      FloatImage blank(width, height), bar(width, height);
      draw_color_bar(bar, ColorMap::viridis, {-35000, -0.000125}, "a title", side);
      const LegendMargins m = color_bar_margins(width, height, side);
      const int s = text_scale(height), below_title = height / 10 - 7 * s / 2 - s;
      int x0 = width, x1 = -1;
      for (int y = below_title; y < height; ++y)
        for (int x = 0; x < width; ++x)
          if (bar.at(x, y) != blank.at(x, y)) x0 = std::min(x0, x), x1 = std::max(x1, x);
      ASSERT_LE(x0, x1);
      if (side == BarSide::right) {
        EXPECT_GE(x0, width - m.right) << width;
        EXPECT_LT(x0, width - m.right + 3 * s) << width << ": margins wider than needed";
      } else {
        EXPECT_LT(x1, m.left) << width;
        EXPECT_GE(x1, m.left - 3 * s) << width << ": margins wider than needed";
      }
    }
}

// With the fluid framed clear of the bar, the glyphs (the pixels that another colour map
// changes, the bar's own rectangle left out) stop short of the bar's margin.
TEST(Annotations, TheFluidIsFramedClearOfTheColourBar) {
  const int bar = std::max(4, kWidth / 40);
  const LegendMargins m = color_bar_margins(kWidth, kHeight, BarSide::right);
  ASSERT_GT(m.right, 2 * bar);
  const FloatImage a = picture("caption: '', color_map: viridis, units: m/s");
  const FloatImage b = picture("caption: '', color_map: plasma, units: m/s");
  int glyph_right = -1;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const bool in_bar = x >= kWidth - 2 * bar && x < kWidth - bar && y >= kHeight / 10 &&
                          y < kHeight - kHeight / 10;
      if (!in_bar && a.at(x, y) != b.at(x, y)) glyph_right = std::max(glyph_right, x);
    }
  ASSERT_GE(glyph_right, 0) << "no glyph";
  EXPECT_LT(glyph_right, kWidth - m.right);
  EXPECT_GT(glyph_right, kWidth - m.right - kWidth / 5) << "the fluid not framed up to it";
}

TEST(Annotations, CaptionFieldsAreFilledFromTheStep) {
  std::string out;
  expand_caption("{view}: step {step}, t = {time} s", {1200, 0.123456, "front"}, out);
  EXPECT_EQ(out, "front: step 1200, t = 0.1235 s");
  expand_caption("no fields", {}, out);
  EXPECT_EQ(out, "no fields");
  EXPECT_EQ(caption_problem("t = {time}"), "");
}

TEST(Annotations, ABadCaptionIsRefusedWithItsLine) {
  test::expect_refused_with_line("particles",
                                 {{"caption: 't = {tme}'", "unknown field {tme}"},
                                  {"caption: 't = {time'", "has a '{' with no '}'"},
                                  {"caption: \"caf\\u00e9\"", "printable ASCII only"},
                                  {"caption: '" + std::string(kCaptionMaxLength + 1, 'a') + "'",
                                   "longer than 200 characters"}});
}

}  // namespace
}  // namespace voxspan
