// What a picture says of itself: the colour bar's title (the quantity, its `units`) and a view's
// `caption` with the step's numbers, through the runtime; the caption's pattern refused with
// its line when it names a field that does not exist.
#include <gtest/gtest.h>

#include <string>

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
  // The title row: above the bar (its top at a tenth of the height), flush with its right edge.
  EXPECT_LT(d.y1, kHeight / 10 - 3);
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
