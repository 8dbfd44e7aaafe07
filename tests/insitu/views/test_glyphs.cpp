// The particle glyphs (insitu/views/glyphs.h) against the brute-force ray-sphere render of the
// same particles (every pixel's ray against every sphere, in double): the same nearest
// particle, depth, normal and value at every pixel, so the same picture, with every culling
// mode (culling never changes a pixel), whatever the thread count. Also: the culling does cull
// on a dense block, the parameter range and the shell select what they say, a sphere straight
// ahead has the depth it must have, and missing attributes are refused by name.
#include "insitu/views/glyphs.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "tools/scenes/scene_cell_states.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr double kSpacing = 0.1;

// A dense jittered block with a speed field, a spray of droplets above it, a few particles
// behind the camera, and the grid's cell states (cells of 2 spacings, full at 6 particles).
struct Scene {
  std::vector<double> x, y, z, speed;
  std::vector<float> velocity;
  test::TestCells cells;

  Scene() {
    std::uint64_t seed = 7;
    auto random = [&] {
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      return double(seed >> 11) / double(1ULL << 53);
    };
    auto add = [&](double px, double py, double pz) {
      x.push_back(px), y.push_back(py), z.push_back(pz);
      speed.push_back(std::sqrt(px * px + pz) + py);
      for (double c : {py, -px, 0.3 * pz}) velocity.push_back(float(c));
    };
    for (int k = 0; k < 16; ++k)
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 24; ++i)
          add((i + 0.5 + 0.3 * (random() - 0.5)) * kSpacing,
              (j + 0.5 + 0.3 * (random() - 0.5)) * kSpacing,
              (k + 0.5 + 0.3 * (random() - 0.5)) * kSpacing);
    for (int d = 0; d < 300; ++d) add(2.4 * random(), 1.3 + 0.8 * random(), 1.6 * random());
    for (int d = 0; d < 5; ++d) add(1.2 + 0.1 * d, 0.6, 9.0 + d);  // behind the eye
    std::vector<ParticleSphere> spheres;
    for (std::size_t i = 0; i < x.size(); ++i)
      spheres.push_back({float(x[i]), float(y[i]), float(z[i]), float(kSpacing)});
    cells = test::classify_for_test(spheres, 2 * kSpacing, 6);
  }
  ParticleView view() const {
    return ParticleView::soa(x.data(), y.data(), z.data(), x.size())
        .with_scalar("speed", speed.data())
        .with_vector("velocity", velocity.data());
  }
};

Camera camera(glm::dvec3 eye, glm::dvec3 target, int w = 96, int h = 64) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.fov_y_degrees = 50;
  c.width = w;
  c.height = h;
  return c;
}

GlyphSelection selection(GlyphCulling culling, double radius = 0.6 * kSpacing) {
  GlyphSelection s;
  s.radius = radius;
  s.color_by = "velocity";
  s.culling = culling;
  return s;
}

void expect_same(const GlyphImage& a, const GlyphImage& b, const char* what) {
  ASSERT_EQ(a.nearest.size(), b.nearest.size());
  std::size_t differ = 0, hits = 0;
  for (std::size_t k = 0; k < a.nearest.size(); ++k) {
    hits += a.nearest[k] != kNoGlyph;
    if (a.nearest[k] != b.nearest[k] || a.depth[k] != b.depth[k] || a.value[k] != b.value[k] ||
        a.normal[k] != b.normal[k])
      ++differ;
  }
  EXPECT_EQ(differ, 0u) << what << ": " << differ << " of " << a.nearest.size() << " pixels";
  EXPECT_GT(hits, a.nearest.size() / 10) << what << ": the scene should fill the picture";
}

TEST(Glyphs, EveryCullingModeGivesTheBruteForcePicture) {
  const Scene s;
  const ParticleView p = s.view();
  for (const Camera& cam : {camera({4.0, 3.5, 5.0}, {1.2, 0.6, 0.8}),
                            camera({1.2, 0.7, 2.2}, {1.2, 0.6, 0.0}),     // inside the block's box
                            camera({1.0, 0.6, 0.9}, {2.0, 0.6, 0.9})}) {  // among the particles
    GlyphImage reference, fast;
    reference_glyphs(p, s.cells.view, cam, selection(GlyphCulling::none), reference);
    FloatImage reference_picture, fast_picture;
    GlyphShading shading;
    shading.by_value = true;
    shading.axis = {0, 2};
    shading.ao_radius = 4 * 0.6 * kSpacing;
    shade_glyphs(reference, cam, shading, reference_picture);
    for (GlyphCulling culling :
         {GlyphCulling::none, GlyphCulling::frustum, GlyphCulling::occlusion}) {
      rasterize_glyphs(p, s.cells.view, cam, selection(culling), fast);
      const std::string name(name_of<GlyphCulling>(kGlyphCullingNames, culling));
      expect_same(fast, reference, name.c_str());
      EXPECT_EQ(fast.counts.selected(), reference.counts.drawn) << name;
      EXPECT_EQ(fast.values.lo, reference.values.lo) << name;
      EXPECT_EQ(fast.values.hi, reference.values.hi) << name;
      shade_glyphs(fast, cam, shading, fast_picture);
      EXPECT_EQ(fast_picture.rgba, reference_picture.rgba) << name;
    }
  }
}

TEST(Glyphs, CullingSkipsWhatCannotShow) {
  const Scene s;
  const ParticleView p = s.view();
  // From outside, looking at the block's corner: its inner-full cells lie behind the shell.
  const Camera outside = camera({4.0, 3.5, 5.0}, {1.2, 0.6, 0.8});
  GlyphImage none, frustum, occlusion;
  rasterize_glyphs(p, s.cells.view, outside, selection(GlyphCulling::none), none);
  rasterize_glyphs(p, s.cells.view, outside, selection(GlyphCulling::occlusion), occlusion);
  EXPECT_EQ(none.counts.drawn, none.counts.selected());
  EXPECT_GT(occlusion.counts.cells_hidden, 60);
  EXPECT_GT(occlusion.counts.occlusion_culled, none.counts.drawn / 5);
  EXPECT_LT(occlusion.counts.drawn, none.counts.drawn);
  // Close up, half the block is out of the view.
  const Camera close = camera({0.6, 0.6, 2.0}, {0.6, 0.6, 0.0});
  rasterize_glyphs(p, s.cells.view, close, selection(GlyphCulling::frustum), frustum);
  EXPECT_GT(frustum.counts.frustum_culled, frustum.counts.selected() / 4);
  EXPECT_EQ(frustum.counts.holding_eye, 0);
}

TEST(Glyphs, TheSameWithOneThreadOrMany) {
  const Scene s;
  const ParticleView p = s.view();
  const Camera cam = camera({4.0, 3.5, 5.0}, {1.2, 0.6, 0.8}, 160, 90);
  GlyphImage many, one;
  rasterize_glyphs(p, s.cells.view, cam, selection(GlyphCulling::occlusion), many);
  {
    tbb::global_control serial(tbb::global_control::max_allowed_parallelism, 1);
    rasterize_glyphs(p, s.cells.view, cam, selection(GlyphCulling::occlusion), one);
  }
  expect_same(many, one, "1 thread");
}

TEST(Glyphs, RangeAndShellSelectWhatTheySay) {
  const Scene s;
  const ParticleView p = s.view();
  const Camera cam = camera({4.0, 3.5, 5.0}, {1.2, 0.6, 0.8});
  GlyphSelection ranged = selection(GlyphCulling::occlusion);
  ranged.cull_by = "speed";
  ranged.cull_range = std::array<double, 2>{1.0, 2.6};
  GlyphImage fast, reference;
  rasterize_glyphs(p, s.cells.view, cam, ranged, fast);
  reference_glyphs(p, s.cells.view, cam, ranged, reference);
  expect_same(fast, reference, "cull_range");
  EXPECT_GT(fast.counts.range_culled, 0);
  for (std::size_t k = 0; k < fast.nearest.size(); ++k)
    if (fast.nearest[k] != kNoGlyph) {
      const double v = s.speed[fast.nearest[k] & 0xffffffffu];
      ASSERT_TRUE(v >= 1.0 && v <= 2.6) << v;
    }
  GlyphSelection shell = selection(GlyphCulling::occlusion);
  shell.boundary_only = true;
  rasterize_glyphs(p, s.cells.view, cam, shell, fast);
  reference_glyphs(p, s.cells.view, cam, shell, reference);
  expect_same(fast, reference, "boundary");
  EXPECT_GT(fast.counts.inner_skipped, 0);
  EXPECT_EQ(fast.counts.occlusion_culled, 0);  // no inner-full particle is left to cull
}

TEST(Glyphs, ASphereStraightAheadIsWhereItMustBe) {
  const double xyz[3] = {0, 0, 0};
  const ParticleView p = ParticleView::aos(xyz, 1);
  const Camera cam =
      camera({0, 0, 3}, {0, 0, 0}, 33, 33);  // odd: the centre pixel's ray is the axis
  GlyphSelection s;
  s.radius = 0.5;
  GlyphImage g;
  rasterize_glyphs(p, CellStatesView{}, cam, s, g);
  const std::size_t centre = 16 + 33 * 16;
  EXPECT_EQ(g.depth[centre], 2.5f);
  EXPECT_NEAR(g.normal[centre].z, -1.0f, 1e-6f);  // facing the eye (view z points forward)
  // The silhouette: pixel centres within the sphere's cone are hit, those outside are not.
  const ViewFrame f(cam);
  for (int y = 0; y < 33; ++y)
    for (int x = 0; x < 33; ++x) {
      const glm::dvec3 v = glm::normalize(f.view_ray(x, y));
      const bool inside = std::acos(v.z) < std::asin(0.5 / 3.0);
      EXPECT_EQ(g.nearest[std::size_t(x) + 33 * std::size_t(y)] != kNoGlyph, inside)
          << x << " " << y;
    }
}

TEST(Glyphs, MissingAttributesAreRefusedByName) {
  const Scene s;
  const ParticleView p = s.view();
  GlyphImage g;
  GlyphSelection by = selection(GlyphCulling::none);
  by.color_by = "pressure";
  const Camera cam = camera({4, 3, 5}, {1, 0.6, 0.8});
  try {
    rasterize_glyphs(p, s.cells.view, cam, by, g);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("color_by \"pressure\""), std::string::npos) << e.what();
  }
  GlyphSelection cull = selection(GlyphCulling::none);
  cull.cull_by = "age";
  cull.cull_range = std::array<double, 2>{0, 1};
  EXPECT_THROW(rasterize_glyphs(p, s.cells.view, cam, cull, g), Error);
}

}  // namespace
}  // namespace voxspan
