// A user's first picture: the dam break with no view configured (the default view, its
// automatic camera and absorption: auto), at a column 1 cm wide and at one 100 m wide, through
// the shared library as a solver links it. The water must stand out from what lies around it:
// the water pixels (where the depth image has a hit) are tinted against the background pixels
// (none), and not black. The old default, clear water's absorption in metres at any scale, is
// measured beside it: nearly invisible at 1 cm.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace voxspan
