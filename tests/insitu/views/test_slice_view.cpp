// views[i] of kind `slice` through the runtime: its keys read and refused as documented, the
// picture coloured where the plane meets the fluid and dark where it does not, a quantity the
// solver does not pass failing the step by name, and a plane that misses the fluid drawing
// an empty picture. The interpolation itself: test_sph_slice.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "insitu/views/legend.h"
#include "insitu/views/slice_view.h"
#include "tests/support/view_tests.h"

namespace voxspan {
namespace {

// A block 1.0 x 0.5 x 0.5 with density rising along x.
test::ParticleBlock block() {
  return {0.05, "density", [](int, double x) { return 1000 + 10 * x; }};
}

std::string config(const std::string& slice, const std::string& size = "width: 64, height: 32") {
  // No caption: the tests read the picture's corners.
  return test::one_view_config("slice_view",
                               "name: s, kind: slice, caption: '', " + size + ", " + slice);
}

const FloatImage& picture_of(const Adapter& a) { return *test::latest_view(a).picture; }

TEST(SliceView, KeysAreReadAsWritten) {
  const SliceSettings s = test::read_view<SliceSettings>(
      "kind: slice, quantity: p, kernel: quintic, shepard: true, range: [1, 2],"
      " color_map: coolwarm, plane: {origin: [1, 2, 3], normal: [0, 0, 2]}, isolines: 0");
  EXPECT_EQ(s.quantity, "p");
  EXPECT_EQ(s.kernel, SphKernel::quintic);
  EXPECT_TRUE(s.shepard);
  ASSERT_TRUE(s.range);
  EXPECT_EQ((*s.range)[1], 2.0);
  EXPECT_EQ(s.color_map, ColorMap::coolwarm);
  EXPECT_EQ(s.plane.normal[2], 2.0);
}

TEST(SliceView, BadKeysAreRefusedWithTheirLine) {
  test::expect_refused_with_line(
      "slice", {{"color_map: rainbow, quantity: p", "color_map"},
                {"range: [2, 1], quantity: p", "range"},
                {"range: [0, .inf], quantity: p", "[min, max] of finite numbers; got [0, inf]"},
                {"plane: {normal: [0, 0, 0]}, quantity: p", "must not be zero"},
                {"kernel: gauss, quantity: p", "kernel"},
                {"width: 10", "needs `quantity`"}});
}

TEST(SliceView, ColoursThePlaneWhereItMeetsTheFluid) {
  const test::ParticleBlock b = block();
  const FloatImage p = test::first_picture(
      config("quantity: density, shepard: true, plane: {normal: [0, -1, 0]}, isolines: 0"), b);
  // The plane through the box's centre seen from -y (its normal's side), fitted: +x to the
  // right. The left of the picture is the low density end (viridis: dark blue), the right the
  // high end (yellow-green); the colour bar is further right.
  const glm::vec4 left = p.at(6, 9), right = p.at(50, 9);  // between the legend's labels
  EXPECT_GT(left.b, left.g);
  EXPECT_GT(right.g, right.b);
  EXPECT_GT(right.r + right.g, left.r + left.g);
}

// The range's ends are no isolines: a field that rises to its maximum at x = 0.5 and stays there
// has its last isoline at x = 0.375 (3 isolines), none where the plateau begins (the pixels at
// the maximum of an automatic range were ringed).
TEST(SliceView, IsolinesStayInsideTheRange) {
  const test::ParticleBlock b{0.05, "density", [](int, double x) { return std::min(x, 0.5); }};
  const FloatImage p = test::first_picture(
      config("quantity: density, shepard: true, plane: {normal: [0, -1, 0]}, isolines: 3",
             "width: 256, height: 128"),
      b);
  const int row = 64;  // the fluid spans about 116 pixels of it: 0.125 in x is 14
  int plateau = 0;
  while (plateau < p.width && !(p.at(plateau, row).r > 0.9f && p.at(plateau, row).b < 0.1f))
    ++plateau;  // viridis' yellow end
  ASSERT_LT(plateau, p.width);
  int end = plateau;
  while (end < p.width && p.at(end, row).r > 0.2f) ++end;  // dots in the plateau end no run
  int dark = 0;
  for (int y = row - 20; y <= row + 20; ++y)
    for (int x = plateau - 6; x < end - 1; ++x) dark += p.at(x, y).g < 0.4f;
  EXPECT_EQ(dark, 0) << "in the plateau, x from " << plateau << " to " << end;
}

TEST(SliceView, AMissingQuantityFailsTheStepByName) {
  // The key with the line the config gave the view on.
  test::expect_missing_attribute(config("quantity: pressure"), block(),
                                 "<config>:5:5: views[0].quantity", "pressure");
}

TEST(SliceView, APlaneThatMissesTheFluidDrawsAnEmptyPicture) {
  const test::ParticleBlock b = block();
  const FloatImage p = test::first_picture(
      config("quantity: density, plane: {origin: [0, 0, 9], normal: [0, 0, 1]}"), b);
  for (int x : {0, 10, 30}) EXPECT_LT(p.at(x, 16).g, 0.05f) << x;
}

bool light(glm::vec4 c) { return c.r > 0.8f && c.g > 0.8f && c.b > 0.8f; }

TEST(SliceView, AxesTickRoundValuesInWorldUnits) {
  const test::ParticleBlock b = block();
  // Seen from -y with +z up: +x to the right, x from -0.3 to 1.3 over 320 pixels and z from
  // -0.2 to 0.7 over 180 rows. Ticks every 0.2 (-0.2 to 1.2), the middle one (0.6) named.
  Adapter a =
      adapter_from_config_text(config("quantity: density, extent: 1.6,"
                                      " plane: {origin: [0.5, 0.25, 0.25], normal: [0, -1, 0]}",
                                      "width: 320, height: 180"),
                               test::spaced(b.spacing));
  ASSERT_TRUE(a.execute(0, 0, b.view()).ok());
  const FloatImage& p = picture_of(a);
  for (const double x : {0.0, 0.4, 1.0}) {
    const int column = int(std::lround((x + 0.3) / 1.6 * 320));
    EXPECT_TRUE(light(p.at(column, 179))) << x;
    EXPECT_FALSE(light(p.at(column + 10, 179))) << x;
  }
  int label = 0;  // "x=0.6" above the middle tick, at column 180
  for (int y = 160; y < 176; ++y)
    for (int x = 164; x < 197; ++x) label += light(p.at(x, y));
  EXPECT_GT(label, 20);
  // z ticks every 0.2 on the left edge (z = 0.4 at row 180 - 0.6 / 0.9 * 180 = 60).
  EXPECT_TRUE(light(p.at(0, 60)));
  EXPECT_FALSE(light(p.at(0, 70)));
}

// The centre pixel of an opaque surface view of the block seen from +z, with `slice` keys.
glm::vec4 surface_centre(const std::string& slice) {
  const test::ParticleBlock b = block();
  Adapter a =
      adapter_from_config_text("output_folder: " + testing::TempDir() +
                                   "slice_in_surface\n"
                                   "outputs: {png: {enabled: false}, stats: {enabled: false}}\n"
                                   "views:\n  - {name: w, shading: opaque, width: 96, height: 54,"
                                   " camera: {direction: [0, 0, -1], up: [0, 1, 0]}" +
                                   slice + "}\n",
                               test::spaced(b.spacing));
  EXPECT_TRUE(a.execute(0, 0, b.view()).ok());
  return picture_of(a).at(48, 27);
}

TEST(SliceView, InASurfaceViewItShowsWhereItLiesInFrontOfTheWater) {
  const std::string keys =
      "quantity: density, shepard: true, range: [1000, 1010], color_map: coolwarm,"
      " isolines: 0, smoothing_length: 0.1, plane: {normal: [0, 0, 1], ";
  const glm::vec4 water = surface_centre("");
  // Inside the block, under its top: hidden.
  EXPECT_EQ(surface_centre(", slice: {" + keys + "origin: [0.5, 0.25, 0.25]}}"), water);
  // Above the top (z = 0.5), still within the kernel's reach of the top layer: in front.
  const glm::vec4 above = surface_centre(", slice: {" + keys + "origin: [0.5, 0.25, 0.55]}}");
  EXPECT_NE(above, water);
  EXPECT_NEAR(above.r, above.b, 0.15f);  // coolwarm's middle, light grey
}

TEST(Legend, AFallingAxisTicksFromTheRight) {
  FloatImage p(400, 200);
  draw_axes(p, {1.0, 0.0, "u"}, {0.0, 1.0, "v"});
  // u = 0.8 lies at 0.2 of the width from the left.
  EXPECT_TRUE(light(p.at(80, 199)));
  EXPECT_FALSE(light(p.at(90, 199)));
  FloatImage small(100, 60);
  draw_axes(small, {0.0, 1.0, "u"}, {0.0, 1.0, "v"});
  for (int x = 0; x < 100; ++x) EXPECT_FALSE(light(small.at(x, 59))) << x;
}

// Values printed side by side have the digits that tell them apart: a field of 300 to 300.05 K,
// a slice at x = 1e4; a value that is zero at the legend's resolution prints as 0.
TEST(Legend, NumbersHaveTheDigitsThatTellThemApart) {
  EXPECT_EQ(legend_number(0.125), "0.125");
  EXPECT_EQ(legend_number(-35000), "-3.5e+04");
  EXPECT_EQ(legend_number(300, 0.025), "300");
  EXPECT_EQ(legend_number(300.025, 0.025), "300.025");
  EXPECT_EQ(legend_number(300.05, 0.025), "300.05");
  EXPECT_EQ(legend_number(10000.5, 0.5), "10000.5");
  EXPECT_EQ(legend_number(4.2e6 + 20, 10), "4200020");
  EXPECT_EQ(legend_number(2.48e-16, 0.5), "0");
  EXPECT_EQ(legend_number(0.5, 0.5), "0.5");
}

}  // namespace
}  // namespace voxspan

namespace voxspan {
namespace {

TEST(SliceView, AnAutomaticPlaneFitsTheFluidClearOfTheLegend) {
  const test::ParticleBlock b = block();
  constexpr int kW = 320, kH = 180;
  const std::string run =
      "output_folder: " + testing::TempDir() + "slice_margins\n" +
      "outputs: {png: {enabled: false}, stats: {enabled: false},\n"
      "          exr: {enabled: true, trigger: {every_steps: 1}}}\n"
      "writer: {fsync: false}\n"
      "trigger: {every_steps: 1}\n"
      "views:\n  - {name: s, kind: slice, width: 320, height: 180, quantity: density,"
      " plane: {normal: [0, -1, 0]}}\n";
  Adapter a = adapter_from_config_text(run, test::spaced(b.spacing));
  ASSERT_TRUE(a.execute(0, 0, b.view()).ok());
  const FieldImage* field = test::latest_view(a).field;
  ASSERT_NE(field, nullptr);
  const LegendMargins m = legend_margins(kW, kH);
  ASSERT_GT(m.right, 0);
  int reached = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (!(field->values.at(x, y).g > 0)) continue;
      ++reached;
      EXPECT_TRUE(x >= m.left && x < kW - m.right && y >= m.top && y < kH - m.bottom)
          << "fluid under the legend at " << x << ", " << y;
    }
  EXPECT_GT(reached, kW * kH / 8);
}

}  // namespace
}  // namespace voxspan
