// A surface view's `color_by` (insitu/views/surface_colors.h): the attribute interpolated at the
// first surface of a block whose attribute is its x coordinate gives each pixel its hit point's
// x; through the runtime the GL and the CPU renderer colour alike, the map's ends where the
// attribute's are, an empty color_by changes nothing, a missing attribute fails the step by
// name and bad keys are refused with their line; colouring adds no texture to the surface.
// Under MPI: tests/mpi/views.yaml.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "insitu/views/surface_colors.h"
#include "insitu/views/surface_view.h"
#include "tests/support/view_tests.h"

namespace voxspan {
namespace {

// A block 1.0 x 0.5 x 0.5 whose attribute `x` is each particle's x.
test::ParticleBlock block() {
  return {0.05, "x", [](int, double x) { return x; }};
}

std::string config(const std::string& keys, const std::string& backend = "cpu") {
  return "renderer: {backend: " + backend + "}\n" +
         test::one_view_config("surface_colors",
                               "name: s, caption: '', width: 96, height: 64, camera: {direction: "
                               "[0.2, 0.5, -1], up: [0, 0, 1]}, " +
                                   keys);
}

TEST(SurfaceColors, TheValueAtTheFirstSurfaceIsTheAttributeThere) {
  const test::ParticleBlock b = block();
  Camera camera;
  camera.eye = {0.5, 0.25, 2.0};
  camera.target = {0.5, 0.25, 0.0};
  camera.width = 80, camera.height = 60;
  // The block's top face (its spheres' tops, z = 0.5) as the first hit.
  const ViewFrame f(camera);
  FloatImage first_hit(camera.width, camera.height);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const glm::dvec3 ray = f.world_ray(x, y);
      const glm::dvec3 hit = f.eye + (0.5 - f.eye.z) / ray.z * ray;
      if (hit.x > 0 && hit.x < 1 && hit.y > 0 && hit.y < 0.5)
        first_hit.set(x, y, glm::vec4(float((0.5 - f.eye.z) / ray.z * f.ray_scale(x, y)), 0, 0, 0));
    }
  ColorBySettings s;
  s.color_by = "x";
  SurfaceColors colors(s, "v", "views[0].color_by", b.spacing, nullptr);
  colors.sample(b.view(), camera, &first_hit, "");
  int checked = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const glm::dvec3 ray = f.world_ray(x, y);
      const glm::dvec3 hit = f.eye + (0.5 - f.eye.z) / ray.z * ray;
      if (!(first_hit.at(x, y).r > 0)) {
        EXPECT_TRUE(std::isnan(colors.value(x, y))) << x << " " << y;
        continue;
      }
      // Inside the lattice's ends (Shepard's sum there leans towards the particles'
      // mean), within a twentieth of a spacing.
      if (hit.x < 0.15 || hit.x > 0.85) continue;
      EXPECT_NEAR(colors.value(x, y), hit.x, 0.05 * b.spacing) << x << " " << y;
      ++checked;
    }
  EXPECT_GT(checked, 500);
  EXPECT_NEAR(colors.axis().lo, 0.025, 0.02);
  EXPECT_NEAR(colors.axis().hi, 0.975, 0.02);
}

double mean_difference(const FloatImage& a, const FloatImage& b) {
  double sum = 0;
  for (std::size_t k = 0; k < a.rgba.size(); ++k) sum += std::abs(a.rgba[k] - b.rgba[k]);
  return sum / double(a.rgba.size());
}

TEST(SurfaceColors, BothRenderersColourAlikeWithTheMapsEndsAtTheAttributes) {
  const test::ParticleBlock b = block();
  for (const char* shading : {"opaque", "translucent", "refractive"}) {
    const std::string keys = std::string("shading: ") + shading;
    const std::string by_x = keys + ", color_by: x, legend: false";
    const FloatImage cpu = test::first_picture(config(by_x), b);
    const FloatImage gl = test::first_picture(config(by_x, "gl"), b);
    const double plain = mean_difference(test::first_picture(config(keys), b),
                                         test::first_picture(config(keys, "gl"), b));
    // The colouring adds little to what the two renderers' shading already differ by.
    EXPECT_LT(mean_difference(cpu, gl), 1.5 * plain + 0.004) << shading;
    for (const FloatImage* p : {&cpu, &gl}) {
      // The block's middle row, low x at the left: viridis runs from blue to yellow-green.
      const glm::vec4 left = p->at(32, 30), right = p->at(66, 30);
      EXPECT_GT(left.b, left.r) << shading;
      EXPECT_GT(right.g, right.b) << shading;
      EXPECT_GT(right.r, left.r) << shading;
    }
  }
}

// Pixels of `p` more than `by` off the median of their 3x3 neighbourhood in some channel.
int rough_pixels(const FloatImage& p, float by) {
  int count = 0;
  for (int y = 1; y + 1 < p.height; ++y)
    for (int x = 1; x + 1 < p.width; ++x)
      for (int c = 0; c < 3; ++c) {
        std::array<float, 9> n;
        for (int k = 0; k < 9; ++k) n[std::size_t(k)] = p.at(x + k % 3 - 1, y + k / 3 - 1)[c];
        std::nth_element(n.begin(), n.begin() + 4, n.end());
        if (std::abs(p.at(x, y)[c] - n[4]) > by) {
          ++count;
          break;
        }
      }
  return count;
}

// The colours' Fresnel blend reads the normals of the surface the picture shows (filtered), not
// the cast's first entries, whose spheres' bumps made a lattice of dots on a calm top: colouring
// adds no texture to the water's surface, on either renderer.
TEST(SurfaceColors, ColouringAddsNoTextureToTheSurface) {
  const test::ParticleBlock b = block();
  // Twice the other tests' size: a particle a few pixels wide.
  const auto larger = [](std::string c) {
    return c.replace(c.find("width: 96, height: 64"), 21, "width: 192, height: 128");
  };
  for (const char* backend : {"cpu", "gl"}) {
    const std::string keys = "shading: translucent";
    const int plain = rough_pixels(test::first_picture(larger(config(keys, backend)), b), 0.02f);
    const int colored = rough_pixels(
        test::first_picture(larger(config(keys + ", color_by: x, legend: false", backend)), b),
        0.02f);
    std::printf("%s: %d rough pixels plain, %d coloured\n", backend, plain, colored);
    // The map's hues add edges against the ground (253 -> 402 on the CPU, 0.6 % of the
    // picture's 192 x 128 pixels); the bumps' lattice of dots added 958 (3.9 %).
    EXPECT_LT(colored - plain, 192 * 128 / 100) << backend;
  }
}

TEST(SurfaceColors, AnEmptyColorByChangesNothing) {
  const test::ParticleBlock b = block();
  const FloatImage plain = test::first_picture(config("shading: translucent"), b);
  const FloatImage empty =
      test::first_picture(config("shading: translucent, color_by: '', color_map: plasma"), b);
  EXPECT_EQ(plain.rgba, empty.rgba);
}

TEST(SurfaceColors, AMissingAttributeFailsTheStepByName) {
  test::expect_missing_attribute(config("color_by: pressure"), block(),
                                 "<config>:6:5: views[0].color_by", "pressure");
}

TEST(SurfaceColors, KeysAreReadAsWrittenAndBadOnesRefused) {
  const SurfaceSettings s = test::read_view<SurfaceSettings>(
      "color_by: velocity, color_map: inferno, range: [0, 2], units: m/s, legend: false");
  EXPECT_EQ(s.color_by, "velocity");
  EXPECT_EQ(s.color_map, ColorMap::inferno);
  ASSERT_TRUE(s.range);
  EXPECT_EQ((*s.range)[1], 2.0);
  EXPECT_EQ(s.units, "m/s");
  EXPECT_FALSE(s.legend);
  test::expect_refused_with_line("surface", {{"color_by: p, color_map: rainbow", "color_map"},
                                             {"color_by: p, range: [2, 1]", "range"},
                                             {"color_by: p, legend: maybe", "legend"}});
}

}  // namespace
}  // namespace voxspan
