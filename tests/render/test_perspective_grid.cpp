// The perspective grid ([ZD15] sec. 4.2): layer spacing from alpha, layer count rounded to
// words and capped, near and far fitted to what the camera sees, culling counts, conservative
// sphere footprints, and camera validation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

#include "render/perspective_grid.h"
#include "tools/scenes/scenes.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

Camera camera(int width = 200, int height = 100) {
  return test::look_at({0, 0, 0}, {0, 0, -1}, width, height, 60);
}

TEST(PerspectiveGrid, LayersFollowAlphaAndRoundToWords) {
  GridOptions o;
  o.alpha_degrees = 14;
  const PerspectiveGrid g = PerspectiveGrid::over(camera(), 2.0, 5.0, o);
  const double k = std::tan(14 * std::numbers::pi / 180) * 2 * std::tan(std::numbers::pi / 6) / 100;
  EXPECT_NEAR(g.k_d(), k, 1e-15);
  EXPECT_EQ(g.layers_needed(), static_cast<int>(std::ceil(std::log(2.5) / std::log1p(k))));
  EXPECT_EQ(g.layers() % 32, 0);
  EXPECT_GE(g.layers(), g.layers_needed());
  EXPECT_LT(g.layers(), g.layers_needed() + 32);
  EXPECT_FALSE(g.layer_cap_hit());
  EXPECT_DOUBLE_EQ(g.alpha_degrees(), 14);
  // d_i = d_0 (1 + K_d)^i, each layer K_d times its depth thick, and the grid reaches far.
  EXPECT_DOUBLE_EQ(g.layer_depth(0), 2.0);
  EXPECT_NEAR(g.layer_depth(10), 2.0 * std::pow(1 + k, 10), 1e-12);
  EXPECT_NEAR(g.layer_of(g.layer_depth(123.25)), 123.25, 1e-9);
  EXPECT_NEAR(g.layer_thickness(3.0), k * g.layer_depth(std::floor(g.layer_of(3.0))), 1e-12);
  EXPECT_GE(g.grid_far(), 5.0);
  // Finer alpha, more layers.
  o.alpha_degrees = 3;
  EXPECT_GT(PerspectiveGrid::over(camera(), 2.0, 5.0, o).layers(), 4 * g.layers());
}

TEST(PerspectiveGrid, CapCoarsensTheLayersToStillReachFar) {
  GridOptions o;
  o.alpha_degrees = 0.5;
  o.max_layers = 512;
  const PerspectiveGrid g = PerspectiveGrid::over(camera(), 1.0, 10.0, o);
  EXPECT_TRUE(g.layer_cap_hit());
  EXPECT_EQ(g.layers(), 512);
  EXPECT_GT(g.layers_needed(), 512);
  EXPECT_NEAR(g.grid_far(), 10.0, 1e-9);
  EXPECT_GT(g.alpha_degrees(), 0.5);
  // alpha reached = atan(K_d R_y / (2 tan(fov / 2))).
  const double alpha =
      std::atan(g.k_d() * 100 / (2 * std::tan(std::numbers::pi / 6))) * 180 / std::numbers::pi;
  EXPECT_NEAR(g.alpha_degrees(), alpha, 1e-9);
}

TEST(PerspectiveGrid, FitsNearAndFarToVisibleSpheresAndCountsTheRest) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<ParticleSphere> p = {
      {0, 0, -3, 0.5f},       // visible: depth 2.5 .. 3.5
      {0.5f, 0, -6, 1.0f},    // visible: depth 5 .. 7
      {0, 0, 4, 1.0f},        // behind the camera
      {100, 0, -5, 1.0f},     // outside the frustum's side
      {0, 0, -2, nan},        // invalid
      {0, 0, -2, -1.0f},      // invalid
      {0, 0, -0.01f, 0.05f},  // reaches 0.06 in front of the eye: before the near floor 0.07
  };
  CullCounts counts;
  const PerspectiveGrid g = PerspectiveGrid::fit(camera(), p, GridOptions{}, &counts);
  EXPECT_EQ(counts.visible, 2);
  EXPECT_EQ(counts.behind, 2);
  EXPECT_EQ(counts.outside, 1);
  EXPECT_EQ(counts.invalid, 2);
  EXPECT_NEAR(g.near(), 2.5, 1e-6);
  EXPECT_NEAR(g.far(), 7.0, 1e-6);
}

TEST(PerspectiveGrid, NearFloorWhenTheCameraIsInsideASphere) {
  const std::vector<ParticleSphere> p = {{0, 0, -1, 3.0f}};
  GridOptions o;
  const PerspectiveGrid g = PerspectiveGrid::fit(camera(), p, o);
  EXPECT_NEAR(g.far(), 4.0, 1e-6);
  EXPECT_NEAR(g.near(), 0.01 * 4.0, 1e-9);
  o.min_near = 0.5;
  EXPECT_NEAR(PerspectiveGrid::fit(camera(), p, o).near(), 0.5, 1e-9);
}

TEST(PerspectiveGrid, NothingVisibleGivesAnEmptyGrid) {
  CullCounts counts;
  EXPECT_TRUE(PerspectiveGrid::fit(camera(), {}, GridOptions{}, &counts).empty());
  const std::vector<ParticleSphere> behind = {{0, 0, 5, 1}};
  EXPECT_TRUE(PerspectiveGrid::fit(camera(), behind, GridOptions{}, &counts).empty());
  EXPECT_EQ(counts.behind, 1);
}

TEST(PerspectiveGrid, SpherePixelsHoldEveryPixelWhoseRayHitsAndLittleMore) {
  const PerspectiveGrid g = PerspectiveGrid::over(camera(64, 48), 0.5, 20, GridOptions{});
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0, tight = 0;
  for (int n = 0; n < 400; ++n) {
    const glm::dvec3 c(3 * u(rng), 2 * u(rng), 3 + 2.9 * u(rng));
    const double r = 0.05 + 1.5 * (u(rng) + 1);
    const PixelRect rect = g.sphere_pixels(c, r);
    PixelRect hits{64, 48, -1, -1};
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) {
        const glm::dvec3 d = g.view().view_ray(x, y);
        const double zc = glm::dot(d, c) / glm::dot(d, d);
        const glm::dvec3 perp = c - zc * d;
        if (glm::dot(perp, perp) >= r * r || zc + r <= 0) continue;
        ++tested;
        hits = {std::min(hits.x0, x), std::min(hits.y0, y), std::max(hits.x1, x),
                std::max(hits.y1, y)};
        ASSERT_TRUE(x >= rect.x0 && x <= rect.x1 && y >= rect.y0 && y <= rect.y1)
            << "sphere " << c.x << "," << c.y << "," << c.z << " r " << r << " pixel " << x << ","
            << y;
      }
    // Tight: the silhouette's bounds hold at most one more column or row of pixel centres
    // than the pixels hit, for spheres wholly on screen (the others' extreme points may lie
    // off it; spheres reaching the eye's plane get the whole image).
    if (hits.empty() || c.z - r <= 0 || rect.x0 == 0 || rect.y0 == 0 || rect.x1 == 63 ||
        rect.y1 == 47)
      continue;
    ++tight;
    EXPECT_GE(rect.x0, hits.x0 - 1);
    EXPECT_LE(rect.x1, hits.x1 + 1);
    EXPECT_GE(rect.y0, hits.y0 - 1);
    EXPECT_LE(rect.y1, hits.y1 + 1);
  }
  EXPECT_GT(tested, 10000);
  EXPECT_GT(tight, 50);
}

TEST(Camera, BadCamerasAreErrorsNamingTheField) {
  const auto message = [](Camera c) -> std::string {
    try {
      validate(c);
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  Camera c = camera();
  c.up = {0, 0, 1};
  EXPECT_NE(message(c).find("parallel"), std::string::npos);
  c = camera();
  c.fov_y_degrees = 180;
  EXPECT_NE(message(c).find("fov_y_degrees"), std::string::npos);
  c = camera();
  c.eye.x = std::nan("");
  EXPECT_NE(message(c).find("eye"), std::string::npos);
  c = camera();
  c.height = 20000;
  EXPECT_NE(message(c).find("image size"), std::string::npos);
  EXPECT_EQ(message(camera()), "no error");
}

TEST(Camera, RaysHaveDepthOneAndRowZeroAtTheTop) {
  const ViewFrame v(camera(200, 100));
  EXPECT_DOUBLE_EQ(v.view_ray(3, 7).z, 1.0);
  EXPECT_GT(v.view_ray(0, 0).y, 0);
  EXPECT_LT(v.view_ray(0, 99).y, 0);
  EXPECT_LT(v.view_ray(0, 0).x, 0);
  const glm::dvec3 w = v.world_ray(10, 20);
  EXPECT_NEAR(glm::dot(w, v.forward), 1.0, 1e-12);
  EXPECT_NEAR(v.ray_scale(10, 20), glm::length(w), 1e-12);
}

TEST(Camera, PixelCoordinatesInvertTheRays) {
  const ViewFrame v(camera(200, 100));
  for (const auto& [x, y] : {std::pair{0, 0}, {199, 99}, {37, 64}}) {
    const glm::dvec3 ray = v.view_ray(x, y);
    EXPECT_NEAR(v.pixel_x(ray.x), x, 1e-9);
    EXPECT_NEAR(v.pixel_y(ray.y), y, 1e-9);
  }
}

}  // namespace
}  // namespace voxspan
