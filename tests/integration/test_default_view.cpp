// A user's first picture: the dam break with no view configured (the default view, its
// automatic camera and absorption: auto), at a column 1 cm wide and at one 100 m wide, through
// the shared library as a solver links it. The water must stand out from what lies around it:
// the water pixels (where the depth image has a hit) are tinted against the background pixels
// (none), and not black. The old default, clear water's absorption in metres at any scale, is
// measured beside it: nearly invisible at 1 cm.
#include <gtest/gtest.h>

#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "output_files.h"
#include "temp_folder.h"
#include "tools/scenes/scenes.h"
#include "voxspan/adapter.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

std::vector<float> read_depth(const std::filesystem::path& path, int& width, int& height) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  width = window.max.x - window.min.x + 1;
  height = window.max.y - window.min.y + 1;
  std::vector<float> z(std::size_t(width) * height, 0.0f);
  Imf::FrameBuffer frame;
  frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float),
                               sizeof(float) * std::size_t(width)));
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  return z;
}

struct Contrast {
  double tint = 0;       // mean (blue - red) / 255 of the water pixels minus the background's
  double luminance = 0;  // mean of the water pixels, 0..1
  int water = 0, background = 0;
  int grey_background = 0;  // background pixels whose channels are within 10/255 of each other
};

// Water: pixels with a hit whose 5x5 neighbourhood is all hits (silhouettes left out);
// background: pixels whose 5x5 neighbourhood has none.
Contrast contrast(const test::DecodedPng& png, const std::vector<float>& z) {
  const auto all = [&](int x, int y, bool hit) {
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int u = std::clamp(x + dx, 0, png.width - 1),
                  v = std::clamp(y + dy, 0, png.height - 1);
        if ((z[std::size_t(u) + std::size_t(v) * png.width] > 0) != hit) return false;
      }
    return true;
  };
  double tint_water = 0, tint_back = 0, lum = 0;
  Contrast c;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const std::uint8_t* p = &png.rgba[4 * (std::size_t(x) + std::size_t(y) * png.width)];
      const double tint = (double(p[2]) - double(p[0])) / 255;
      if (all(x, y, true)) {
        tint_water += tint;
        lum += (double(p[0]) + p[1] + p[2]) / (3 * 255.0);
        ++c.water;
      } else if (all(x, y, false)) {
        tint_back += tint;
        ++c.background;
        c.grey_background += std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) <= 10;
      }
    }
  if (c.water > 0 && c.background > 0) {
    c.tint = tint_water / c.water - tint_back / c.background;
    c.luminance = lum / c.water;
  }
  return c;
}

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
  const std::vector<float> depth = read_depth(dir / "depth" / "main_00000001.exr", w, h);
  EXPECT_EQ(w, png.width);
  EXPECT_EQ(h, png.height);
  if (!png.ok || w != png.width || h != png.height) return {};
  return contrast(png, depth);
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
