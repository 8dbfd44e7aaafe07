// views[i] of kind `particles` through the runtime: its keys read and refused as documented,
// the glyphs coloured through the map with the legend beside them, the counts in the step's
// stats, a colour attribute the solver does not pass failing the step by name, and the depth
// the depth output writes. The glyphs themselves: test_glyphs.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "insitu/views/particles_view.h"
#include "tests/support/view_tests.h"

namespace voxspan {
namespace {

constexpr double kSpacing = 0.05;

// A block 1.0 x 0.5 x 0.5 with a speed rising along x.
test::ParticleBlock block() {
  return {kSpacing, "speed", [](int, double x) { return x; }};
}

std::string config(const std::string& keys) {
  return test::one_view_config("particles_view",
                               "name: p, kind: particles, width: 96, height: 54, "
                               "camera: {direction: [0, 0, -1], up: [0, 1, 0]}, " +
                                   keys);
}

TEST(ParticlesView, KeysAreReadAsWritten) {
  const ParticlesSettings s = test::read_view<ParticlesSettings>(
      "kind: particles, color_by: velocity, color_map: coolwarm, range: [0, 2],"
      " cull_by: p, cull_range: [1, 5], draw: boundary, culling: frustum, radius: 0.01,"
      " ambient_occlusion: 0.5, legend: false,"
      " slice: {quantity: p, cut: false, plane: {normal: [1, 0, 0]}}");
  EXPECT_EQ(s.color_by, "velocity");
  EXPECT_EQ(s.color_map, ColorMap::coolwarm);
  ASSERT_TRUE(s.range && s.cull_range);
  EXPECT_EQ((*s.cull_range)[1], 5.0);
  EXPECT_EQ(s.draw, GlyphSubset::boundary);
  EXPECT_EQ(s.culling, GlyphCulling::frustum);
  EXPECT_EQ(s.radius, 0.01);
  EXPECT_FALSE(s.legend);
  EXPECT_EQ(s.slice.quantity, "p");
  EXPECT_FALSE(s.slice.cut);
  EXPECT_EQ(s.slice.plane.normal[0], 1.0);
}

TEST(ParticlesView, BadKeysAreRefusedWithTheirLine) {
  test::expect_refused_with_line(
      "particles", {{"color_map: rainbow", "color_map"},
                    {"culling: some", "culling"},
                    {"range: [2, 1]", "range"},
                    {"radius: -1", "radius"},
                    {"cull_range: [0, 1]", "needs `cull_by` or `color_by`"},
                    {"colour_by: speed", "colour_by"},
                    {"slice: {plane: {normal: [1, 0, 0]}}", "views[0].slice.quantity"},
                    {"slice: {quantity: p, kernel: gauss}", "views[0].slice.kernel"}});
}

TEST(ParticlesView, ColoursTheGlyphsAndDrawsTheLegend) {
  const test::ParticleBlock b = block();
  const FloatImage p = test::first_picture(config("color_by: speed"), b);
  // Seen from +z with +x to the right: slow (viridis: blue-violet) on the left, fast
  // (yellow-green) on the right; the colour bar at the right edge runs from yellow at its top
  // to violet at its bottom.
  const glm::vec4 left = p.at(20, 18), right = p.at(66, 18);  // between the legend's labels
  EXPECT_GT(left.b, left.g);
  EXPECT_GT(right.g, right.b);
  const int bar_x = 96 - 2 * 4 + 1;
  EXPECT_GT(p.at(bar_x, 6).g, p.at(bar_x, 6).b);
  EXPECT_GT(p.at(bar_x, 47).b, p.at(bar_x, 47).g);
  // The corners show the background.
  EXPECT_LT(p.at(0, 0).r + p.at(0, 0).g, 0.1f);
}

TEST(ParticlesView, ReportsWhatItDrewAndCulled) {
  const test::ParticleBlock b = block();
  Adapter a = adapter_from_config_text(config("radius: 0.04"), test::spaced(kSpacing));
  ASSERT_TRUE(a.execute(0, 0, b.view()).ok());
  const FrameStats& stats = *test::latest_view(a).stats;
  EXPECT_GT(stats.count("glyphs_drawn"), 0);
  EXPECT_GT(stats.count("glyphs_occlusion_culled"), 0);
  EXPECT_EQ(stats.count("glyphs_drawn") + stats.count("glyphs_occlusion_culled") +
                stats.count("glyphs_frustum_culled"),
            2000);
}

glm::vec4 centre_of(const std::string& keys, std::int64_t* cut = nullptr) {
  const test::ParticleBlock b = block();
  Adapter a = adapter_from_config_text(config(keys), test::spaced(kSpacing));
  EXPECT_TRUE(a.execute(0, 0, b.view()).ok());
  const auto& view = test::latest_view(a);
  if (cut != nullptr) *cut = view.stats->count("glyphs_cut");
  return view.picture->at(48, 27);
}

TEST(ParticlesView, ASlicePlaneCompositesByDepthAndCutsTheGlyphsInFront) {
  // Seen from +z; the plane z = 0.26 nearly halves the block. Uncut, the glyphs above hide it;
  // cut, the 1000 particles whose spheres reach above it (centres at z >= 0.275) are left out
  // and the plane shows.
  const std::string slice =
      "slice: {quantity: speed, plane: {origin: [0.5, 0.25, 0.26], "
      "normal: [0, 0, 1]}, isolines: 0";
  const glm::vec4 none = centre_of("");
  const glm::vec4 hidden = centre_of(slice + ", cut: false}");
  EXPECT_EQ(hidden, none);
  std::int64_t cut = 0;
  const glm::vec4 shown = centre_of(slice + ", range: [0, 1], color_map: coolwarm}", &cut);
  EXPECT_EQ(cut, 1000);
  // coolwarm at the middle of its range: light grey, no glyph shading's blue.
  EXPECT_NEAR(shown.r, shown.b, 0.15f);
  EXPECT_GT(shown.r, 0.5f);
}

TEST(ParticlesView, AMissingColourAttributeFailsTheStepByName) {
  test::expect_missing_attribute(config("color_by: pressure"), block(),
                                 "<config>:5:5: views[0].color_by", "pressure");
}

}  // namespace
}  // namespace voxspan

namespace voxspan {
namespace {

// Particles moving along +x, one per row, with ids; trails of the even ids.
struct Movers {
  std::vector<double> xyz, id;
  void at_step(int step) {
    xyz.clear();
    id.clear();
    for (int k = 0; k < 6; ++k) {
      for (double c : {0.1 * step, 0.3 * k, 0.0}) xyz.push_back(c);
      id.push_back(100 + k);
    }
  }
  ParticleView view() const {
    return ParticleView::aos(xyz.data(), id.size()).with_scalar("id", id.data());
  }
};

std::string trail_config(const std::string& trails) {
  return test::one_view_config(
      "particles_trails",
      "name: p, kind: particles, width: 160, height: 120, radius: 0.05, ambient_occlusion: 0,"
      " camera: {eye: [0.4, 0.75, 3], target: [0.4, 0.75, 0], up: [0, 1, 0]}, trails: " +
          trails);
}

// Pixels with the trail's colour (more red than blue: the glyphs and background are bluish).
int trail_pixels(const FloatImage& p) {
  int n = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) n += p.at(x, y).r > p.at(x, y).b + 0.2f;
  return n;
}

TEST(ParticlesView, TrailsFollowTheChosenIds) {
  Movers m;
  Adapter a = adapter_from_config_text(trail_config("{every: 2, length: 8}"), test::spaced(0.1));
  std::vector<int> pixels;
  for (int step = 0; step < 8; ++step) {
    m.at_step(step);
    ASSERT_TRUE(a.execute(step, step, m.view()).ok());
    const ViewResult& r = test::latest_view(a);
    EXPECT_EQ(r.stats->count("trails"), 3);  // ids 100, 102, 104
    pixels.push_back(trail_pixels(*r.picture));
  }
  EXPECT_EQ(pixels[0], 0);               // one point: no line yet
  EXPECT_GT(pixels[4], pixels[1] + 10);  // the trails grow as the particles move
  // Three trails of 0.7 world units each, about 34 pixels long at this distance, their older
  // half faded below the count's threshold.
  EXPECT_GT(pixels[7], 3 * 8);
  EXPECT_LT(pixels[7], 3 * 40);
}

TEST(ParticlesView, TrailsNeedTheIdAttribute) {
  const test::ParticleBlock b = block();
  Adapter a =
      adapter_from_config_text(config("trails: {every: 10, id: tag}"), test::spaced(kSpacing));
  const Status s = a.execute(0, 0, b.view());
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message.find("\"tag\""), std::string::npos) << s.message;
}

}  // namespace
}  // namespace voxspan
