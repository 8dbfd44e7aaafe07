// The solver's scenery (Adapter::set_scenery, insitu/views/scenery.h) in surface views through
// the runtime: a closed tank hides its water unless cut away, and then shows it; refracted rays
// end on the walls behind the water; the water's surface goes on behind a wall in front of it
// (no dotted line along the walls); both renderers draw the same tank, at any scale; the keys read
// and refused as documented; particles with NaN positions left out and counted; particles views
// show the tank too, and volume views end their rays at its walls. Under MPI:
// tests/mpi/test_mpi_scenery.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "insitu/views/surface_view.h"
#include "tests/support/image_difference.h"
#include "tests/support/tank.h"
#include "tests/support/view_tests.h"

namespace voxspan {
namespace {

constexpr double kSpacing = 0.05;

test::ParticleBlock water(double spacing = kSpacing) {
  return {spacing, "height", [](int, double x) { return x; }};
}

std::string config(const std::string& keys, const std::string& backend = "cpu") {
  return test::one_view_config("scenery", "name: v, caption: '', width: 96, height: 64, " + keys) +
         "renderer: {backend: " + backend + "}\n";
}

// The picture of one step of `config` with the tank, with or without the water.
FloatImage picture(const std::string& config, bool with_water, double spacing = kSpacing) {
  const test::ParticleBlock w = water(spacing);
  const test::Tank tank(spacing);
  Adapter a = adapter_from_config_text(config, test::spaced(spacing));
  EXPECT_EQ(a.set_scenery(tank.view()), tank.size());
  const ParticleView none = ParticleView::aos(static_cast<const double*>(nullptr), 0);
  const Status s = a.execute(0, 0, with_water ? w.view() : none);
  EXPECT_TRUE(s.ok()) << s.message;
  return s.ok() ? *test::latest_view(a).picture : FloatImage();
}

// Pixels whose colour differs by more than `by` in some channel.
std::vector<bool> differing(const FloatImage& a, const FloatImage& b, float by) {
  std::vector<bool> out(a.rgba.size() / 4, false);
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    if (std::abs(a.rgba[i] - b.rgba[i]) > by) out[i / 4] = true;
  return out;
}

double share(const std::vector<bool>& mask) {
  double n = 0;
  for (bool m : mask) n += m ? 1 : 0;
  return n / double(mask.size());
}

TEST(Scenery, AClosedTankHidesItsWaterUnlessCutAway) {
  const std::string closed = config("shading: translucent, scenery: {cutaway: false}");
  const FloatImage with = picture(closed, true), without = picture(closed, false);
  // The same camera (the framing takes in the tank, which holds the water), the water cut
  // where the walls begin: nothing of it shows.
  EXPECT_LT(test::largest_difference(with.rgba, without.rgba), 1e-6);
  const std::string cut = config("shading: translucent");
  const double shown = share(differing(picture(cut, true), picture(cut, false), 0.02));
  std::printf("the water changes %.1f %% of the cut-away tank's pixels\n", 100 * shown);
  EXPECT_GT(shown, 0.05);
}

TEST(Scenery, RefractedRaysEndOnTheWallsBehindTheWater) {
  // Clear water in a red tank: through the water the rays bend and meet the red walls and
  // floor, not the sky and ground behind the tank.
  const std::string keys =
      "shading: refractive, absorption: [0, 0, 0], scenery: {color: [0.9, 0.05, 0.05]}";
  const FloatImage with = picture(config(keys), true);
  const std::vector<bool> water = differing(with, picture(config(keys), false), 0.002);
  const auto red = [](const FloatImage& p, std::size_t i) {
    return p.rgba[4 * i] > 2 * p.rgba[4 * i + 2];
  };
  double red_water = 0, n = 0;
  for (std::size_t i = 0; i < water.size(); ++i)
    if (water[i]) n += 1, red_water += red(with, i) ? 1 : 0;
  ASSERT_GT(n, 50);
  std::printf("%.0f water pixels, %.1f %% of them red\n", n, 100 * red_water / n);
  EXPECT_GT(red_water / n, 0.6);
}

TEST(Scenery, BothRenderersDrawTheSameTank) {
  for (const char* shading : {"opaque", "translucent", "refractive"}) {
    const std::string keys = std::string("shading: ") + shading;
    const FloatImage cpu = picture(config(keys, "cpu"), true);
    const FloatImage gl = picture(config(keys, "gl"), true);
    const double off = share(differing(cpu, gl, 0.1));
    std::printf("%s: %.2f %% of the pixels more than 0.1 apart\n", shading, 100 * off);
    EXPECT_LT(off, 0.02) << shading;
  }
}

// Far from unit scale the walls are drawn in the frame's units as the water is
// (render/frame_units.h): the tank at 1e-20 and 1e20 times the spacing looks as at the
// spacing itself, on both renderers.
TEST(Scenery, TheTankLooksTheSameAtEveryScale) {
  for (const char* backend : {"cpu", "gl"}) {
    const FloatImage unit = picture(config("shading: refractive", backend), true);
    for (double scale : {1e-20, 1e20}) {
      const FloatImage scaled =
          picture(config("shading: refractive", backend), true, kSpacing * scale);
      const double off = share(differing(unit, scaled, 0.02));
      std::printf("%s at %g: %.2f %% of the pixels more than 0.02 apart\n", backend, scale,
                  100 * off);
      EXPECT_LT(off, 0.005) << backend << " " << scale;
    }
  }
}

// Water pixels more than `by` off their 3x3 neighbourhood's median in some channel (the
// picture's edge left out): dots.
int dots_on_water(const FloatImage& p, const std::vector<bool>& water, float by) {
  int n = 0;
  for (int y = 1; y + 1 < p.height; ++y)
    for (int x = 1; x + 1 < p.width; ++x) {
      const std::size_t i = std::size_t(x) + std::size_t(y) * std::size_t(p.width);
      if (!water[i]) continue;
      bool dot = false;
      for (int c = 0; c < 3; ++c) {
        std::vector<float> around;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) around.push_back(p.at(x + dx, y + dy)[c]);
        std::nth_element(around.begin(), around.begin() + 4, around.end());
        dot = dot || std::abs(p.at(x, y)[c] - around[4]) > by;
      }
      n += dot ? 1 : 0;
    }
  return n;
}

TEST(Scenery, WaterAgainstTheWallsHasNoDotsAlongThem) {
  // The water fills the tank wall to wall: where a wall stands in front of it, its surface goes
  // on behind the wall, and the normals there are the surface's, not a silhouette's (whose
  // edge-on normals reflected the sky in a dotted line along every wall: 46 dots on either
  // renderer, now 13 and 11).
  for (const char* backend : {"cpu", "gl"}) {
    const std::string keys = "shading: translucent";
    const FloatImage with = picture(config(keys, backend), true);
    const std::vector<bool> water = differing(with, picture(config(keys, backend), false), 0.02);
    const int dots = dots_on_water(with, water, 0.1f);
    std::printf("%s: %d dots on the water\n", backend, dots);
    EXPECT_LT(dots, 20) << backend;
  }
}

// A view of kind `keys` shows the tank as a surface view does: a closed one hides the water
// wholly, a cut away one shows it inside (changing at least 5 % of the picture), the walls cover
// at least 20 % of it (against draw: false). Returns the cut-away picture with the water.
FloatImage expect_the_tank_around_the_water(const std::string& keys) {
  const std::string closed = config(keys + ", scenery: {cutaway: false}");
  const FloatImage hidden = picture(closed, true), empty = picture(closed, false);
  EXPECT_LT(test::largest_difference(hidden.rgba, empty.rgba), 1e-6) << keys;
  const std::string cut = config(keys);
  const FloatImage water = picture(cut, true), tank = picture(cut, false);
  const double shown = share(differing(water, tank, 0.02));
  const FloatImage plain = picture(config(keys + ", scenery: {draw: false}"), false);
  const double walls = share(differing(tank, plain, 0.02));
  std::printf("%s: the walls cover %.1f %% of the picture, the water changes %.1f %%\n",
              keys.c_str(), 100 * walls, 100 * shown);
  EXPECT_GT(walls, 0.2) << keys;
  EXPECT_GT(shown, 0.05) << keys;
  return water;
}

TEST(Scenery, ParticleViewsShowTheTankAroundTheirGlyphs) {
  expect_the_tank_around_the_water("kind: particles");
}

// Rays end at the walls: a closed tank hides the water's glow; cut away, its far walls and floor
// stand behind it.
TEST(Scenery, VolumeViewsEndTheirRaysAtTheWalls) {
  const std::string keys = "kind: volume, legend: false";
  const FloatImage glow = expect_the_tank_around_the_water(keys);
  // The GL march ends its rays at the same samples (its sums in float).
  EXPECT_LT(test::largest_difference(glow.rgba, picture(config(keys, "gl"), true).rgba), 1e-4);
}

TEST(Scenery, DrawFalseLeavesThePictureAsWithoutScenery) {
  const test::ParticleBlock w = water();
  const std::string keys = "shading: translucent, scenery: {draw: false}";
  const FloatImage plain = test::first_picture(config("shading: translucent"), w);
  EXPECT_EQ(picture(config(keys), true).rgba, plain.rgba);
}

TEST(Scenery, KeysAreReadAsWrittenAndBadOnesRefused) {
  const SurfaceSettings s = test::read_view<SurfaceSettings>(
      "scenery: {draw: false, color: [1, 0.5, 0], cutaway: false}");
  EXPECT_FALSE(s.scenery.draw);
  EXPECT_FALSE(s.scenery.cutaway);
  EXPECT_EQ(s.scenery.color[1], 0.5);
  test::expect_refused_with_line("surface",
                                 {{"scenery: {colour: [1, 0, 0]}", "colour"},
                                  {"scenery: {color: [-1, 0, 0]}", "must not be negative"},
                                  {"scenery: {draw: maybe}", "draw"}});
}

TEST(Scenery, ParticlesWithoutAPositionAreLeftOutAndCounted) {
  Adapter a = adapter_from_config_text(config("shading: opaque"), test::spaced(kSpacing));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> xyz{0, 0, 0, nan, 0, 0, 1, 0, 0};
  EXPECT_EQ(a.set_scenery(ParticleView::aos(xyz.data(), 3)), 2u);
  EXPECT_EQ(a.set_scenery(ParticleView::aos(xyz.data(), 0)), 0u);  // none: no walls drawn
}

}  // namespace
}  // namespace voxspan
