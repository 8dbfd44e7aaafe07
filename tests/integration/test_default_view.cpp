// A user's first picture: the dam break with no view configured (the default view, its
// automatic camera and absorption: auto), at a column 1 cm wide and at one 100 m wide, through
// the shared library as a solver links it. The water must stand out from what lies around it:
// the water pixels (where the depth image has a hit) are tinted against the background pixels
// (none), and not black. The old default, clear water's absorption in metres at any scale, is
// measured beside it: nearly invisible at 1 cm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "output_files.h"
#include "tests/support/temp_folder.h"
#include "tools/scenes/scenes.h"
#include "voxspan/adapter.h"
#include "voxspan/insitu.h"
#include "water_contrast.h"

namespace voxspan {
namespace {

using test::Contrast;

// The dam break collapsing (column width 0.3, t = 0.3 s) scaled to a column `width` wide,
// rendered by the default view; `view` is extra view config ("" = none at all).
Contrast render_dam_break(double width, const std::string& view) {
  test::TempFolder dir;
  test::DamBreak shape;
  shape.spacing = 0.012;
  shape.radius = 0.012;
  const test::Particles particles = test::dam_break(shape, 0.3);
  const double k = width / shape.width;
  std::vector<double> x, y, z;
  for (const ParticleSphere& p : particles) {
    x.push_back(k * p.x), y.push_back(k * p.y), z.push_back(k * p.z);
  }
  const std::string yaml = "output_folder: " + dir.path().string() + "\n" + view + R"(
trigger: {every_steps: 1}
outputs:
  png: {enabled: true}
  depth: {enabled: true, trigger: {every_steps: 1}}
  stats: {enabled: false}
writer: {fsync: false}
)";
  AdapterOptions options;
  options.classify.particle_spacing = k * shape.spacing;
  {
    Adapter adapter = adapter_from_config_text(yaml, options, "default_view.yaml");
    // The test scene has y up; the default camera's up is z: the particles are rotated so.
    const auto view_of = ParticleView::soa(x.data(), z.data(), y.data(), x.size());
    const Status status = adapter.execute(1, 0.0, view_of);
    EXPECT_TRUE(status.ok()) << status.message;
    adapter.finish();
  }
  const std::filesystem::path picture = dir / "frames" / "main_00000001.png";
  // VOXSPAN_KEEP_PICTURES=DIR keeps the pictures (docs/images/default_view_*.png).
  if (const char* keep = std::getenv("VOXSPAN_KEEP_PICTURES"); keep != nullptr && view.empty())
    std::filesystem::copy_file(
        picture, std::filesystem::path(keep) / ("default_view_" + std::to_string(width) + "m.png"),
        std::filesystem::copy_options::overwrite_existing);
  const test::DecodedPng png = test::read_png_file(picture);
  EXPECT_TRUE(png.ok) << png.error;
  int w = 0, h = 0;
  const std::vector<float> depth = test::read_depth_exr(dir / "depth" / "main_00000001.exr", w, h);
  EXPECT_EQ(w, png.width);
  EXPECT_EQ(h, png.height);
  if (!png.ok || w != png.width || h != png.height) return {};
  return test::water_contrast(png, depth);
}

TEST(DefaultView, TheWaterIsClearlyVisibleAtOneCentimetreAndAtAHundredMetres) {
  const std::string old_default = "views: [{name: main, absorption: [0.45, 0.12, 0.05]}]";
  for (double width : {0.01, 100.0}) {
    const Contrast c = render_dam_break(width, "");
    const Contrast old = render_dam_break(width, old_default);
    std::printf(
        "column %g m wide: water tinted %+.3f against the background, luminance %.2f (%d water, "
        "%d background pixels); absorption in metres: tint %+.3f, luminance %.2f\n",
        width, c.tint, c.luminance, c.water, c.background, old.tint, old.luminance);
    ASSERT_GT(c.water, 1000);
    ASSERT_GT(c.background, 1000);
    EXPECT_GT(c.tint, 0.08) << "the water should stand out, tinted, at " << width << " m";
    EXPECT_GT(c.luminance, 0.3) << "and not black";
    if (width < 1) {
      EXPECT_LT(old.tint, 0.08) << "absorption in metres: clear at 1 cm";
    }
  }
}

TEST(DefaultView, TheGroundAndTheSkyAreTheViewsToChoose) {
  // A red ground and a green sky: every background pixel is one or the other (or, far off, the
  // ground faded into the sky), none the default grey.
  const Contrast c =
      render_dam_break(1.0,
                       "views: [{name: main, ground_light: [1, 0, 0], ground_dark: [1, 0, 0], "
                       "sky_zenith: [0, 1, 0], sky_horizon: [0, 1, 0]}]");
  ASSERT_GT(c.background, 1000);
  EXPECT_LT(c.grey_background, c.background / 100)
      << c.grey_background << " of " << c.background << " background pixels grey";
}

// A 2D run: a right triangle of water, 1 wide and 0.5 tall, its right angle at the lower left,
// in the plane `flat` = 0 (2: PySPH's x-y plane, y up; 1: DualSPHysics' x-z plane, z up),
// rendered by the default view. What the depth image's hits show of it: their box's width over
// its height, and the share of the box's upper quarter that lies in its left half.
struct Seen {
  double aspect = 0, upper_left = 0;
};

Seen render_triangle(int flat, const std::string& backend) {
  test::TempFolder dir;
  const double spacing = 0.02;
  std::vector<double> c[3];
  const int up = flat == 2 ? 1 : 2;
  for (int i = 0; i <= 50; ++i)
    for (int j = 0; j <= 25 - i / 2; ++j) {
      c[0].push_back(i * spacing);
      c[up].push_back(j * spacing);
      c[flat].push_back(0.0);
    }
  const std::string yaml =
      "output_folder: " + dir.path().string() + "\nrenderer: {backend: " + backend + "}" + R"(
trigger: {every_steps: 1}
outputs:
  png: {enabled: false}
  depth: {enabled: true, trigger: {every_steps: 1}}
  stats: {enabled: false}
writer: {fsync: false}
)";
  AdapterOptions options;
  options.classify.particle_spacing = spacing;
  {
    Adapter adapter = adapter_from_config_text(yaml, options, "two_d.yaml");
    const Status status = adapter.execute(
        1, 0.0, ParticleView::soa(c[0].data(), c[1].data(), c[2].data(), c[0].size()));
    EXPECT_TRUE(status.ok()) << status.message;
    adapter.finish();
  }
  int w = 0, h = 0;
  const std::vector<float> depth = test::read_depth_exr(dir / "depth" / "main_00000001.exr", w, h);
  int x0 = w, x1 = -1, y0 = h, y1 = -1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (depth[std::size_t(x + y * w)] > 0)
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  if (x1 < 0) return {};
  int upper = 0, left = 0;  // rows from the top, as the depth image stores them
  for (int y = y0; y <= y0 + (y1 - y0) / 4; ++y)
    for (int x = x0; x <= x1; ++x)
      if (depth[std::size_t(x + y * w)] > 0) ++upper, left += x < (x0 + x1) / 2;
  return {double(x1 - x0 + 1) / double(y1 - y0 + 1), double(left) / std::max(upper, 1)};
}

// A 2D solver's plane is seen head-on with its upward axis up, not as a pane lying on the
// ground seen from above at an angle (the default direction, whose box of the sheet then
// filled a strip of the picture).
TEST(DefaultView, ATwoDimensionalRunIsSeenHeadOnWithItsUpwardAxisUp) {
  for (const char* backend : {"cpu", "gl"})
    for (int flat : {2, 1}) {
      const Seen seen = render_triangle(flat, backend);
      std::printf(
          "%s renderer, 2D run in the plane %c = 0: width / height %.3f (1.02 / 0.52 = "
          "1.96), upper quarter in the left half %.2f\n",
          backend, "xyz"[flat], seen.aspect, seen.upper_left);
      // The particles' radius adds to both sides; perspective nothing, seen head-on.
      EXPECT_NEAR(seen.aspect, 1.96, 0.1) << backend << ", plane " << flat;
      EXPECT_GT(seen.upper_left, 0.95)
          << "the triangle's tall side on the left, up: " << backend << ", plane " << flat;
    }
}

}  // namespace
}  // namespace voxspan
