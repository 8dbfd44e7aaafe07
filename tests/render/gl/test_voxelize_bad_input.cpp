// Inputs a solver will sooner or later hand over: a camera inside the fluid, particles on and
// behind the near plane, a particle bigger than the screen, zero particles, NaN particles, a
// tile budget too small for one tile row, and options out of range. All must work (or fail with
// one clear error naming the input), never crash.
#include <cmath>
#include <limits>
#include <string>

#include "render/gl/tiling.h"
#include "render/reference/exact_spans.h"
#include "tests/render/gl/render_fixture.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/span_compare.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

Camera small_camera(glm::dvec3 eye, glm::dvec3 target) {
  return test::look_at(eye, target, 96, 64);
}

void expect_matches_reference(const SpanImage& gpu, std::span<const ParticleSphere> particles,
                              double gap) {
  const SpanImage ref = exact_spans(gpu.grid, particles, {}, {gap, 0});
  const test::SpanComparison cmp = test::compare_spans(gpu, ref);
  EXPECT_GE(cmp.count_match(), 0.995) << cmp.summary() << test::describe_mismatches(gpu, ref, 4);
  EXPECT_GE(cmp.boundary_match(), 0.995) << cmp.summary();
  EXPECT_LE(cmp.inside_sum_error(), 0.01) << cmp.summary();
}

TEST(VoxelizeBadInput, CameraInsideTheFluid) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  const test::Particles water = test::dam_break(shape, 0.0);
  // The eye in the middle of the column, looking across it.
  const Camera camera = small_camera({0.15, 0.3, 0.15}, {1.0, 0.25, 0.2});
  VoxelizeOptions o;
  o.gap_bridging = shape.spacing;
  o.grid.alpha_degrees = 2;
  o.splat_threads = SplatThreads::per_pixel;
  FrameStats stats;
  const SpanImage gpu = test::voxelize(camera, water, o, {}, &stats);
  // The near plane fell to its floor: a fraction of the far depth, not the eye.
  EXPECT_NEAR(gpu.grid.near(), o.grid.min_near_fraction * gpu.grid.far(), 1e-9);
  // Every ray starts inside the water: its first span begins at the near plane.
  int starting_inside = 0;
  for (int y = 0; y < gpu.height(); ++y)
    for (int x = 0; x < gpu.width(); ++x) {
      const auto spans = gpu.spans_at(x, y);
      ASSERT_FALSE(spans.empty()) << x << "," << y;
      starting_inside += spans[0].entry == float(gpu.grid.near());
    }
  EXPECT_EQ(starting_inside, gpu.width() * gpu.height());
  expect_matches_reference(gpu, water, o.gap_bridging);
  // Spheres around the eye cover the whole screen: the large-sphere splat takes them, whatever
  // the small spheres' thread layout (a single thread marking them all would stop short on
  // llvmpipe, whose shaders stop looping after 65535 iterations).
  EXPECT_GT(stats.count("bin.large"), 0);
  o.splat_threads = SplatThreads::per_particle;
  EXPECT_TRUE(test::identical(gpu, test::voxelize(camera, water, o)));
}

TEST(VoxelizeBadInput, ParticlesOnAndBehindTheNearPlane) {
  const Camera camera = small_camera({0, 0, 0}, {0, 0, -1});
  test::Particles p = test::lattice_block({-0.5, -0.4, -3}, {10, 8, 4}, 0.1, 0.08);
  const std::size_t in_front = p.size();
  p.push_back({0.0f, 0.0f, 0.05f, 0.1f});  // around the eye: reaches both sides of it
  p.push_back({0.2f, 0.1f, 0.5f, 0.2f});   // wholly behind the camera
  p.push_back({-0.3f, 0.0f, 2.0f, 0.5f});  // far behind
  VoxelizeOptions o;
  o.grid.alpha_degrees = 2;
  FrameStats stats;
  const SpanImage gpu = test::voxelize(camera, p, o, {}, &stats);
  EXPECT_EQ(stats.count("particles.culled_behind"), 2);
  EXPECT_EQ(stats.count("particles.visible"), std::int64_t(in_front) + 1);
  // The sphere around the eye reaches every ray from the near plane on.
  EXPECT_EQ(gpu.spans_at(48, 32)[0].entry, float(gpu.grid.near()));
  expect_matches_reference(gpu, p, 0);
}

TEST(VoxelizeBadInput, ParticleBiggerThanTheScreen) {
  const Camera camera = small_camera({0, 0, 10}, {0, 0, 0});
  test::Particles p = test::random_cloud(200, {-1, -1, -1}, {1, 1, 1}, 0.02, 0.1, 4);
  p.push_back({0.0f, 0.0f, -25.0f, 22.0f});  // covers the whole view, behind the cloud
  VoxelizeOptions o;
  o.grid.alpha_degrees = 2;
  o.tiles.max_height = 16;  // in every tile
  o.splat_threads = SplatThreads::per_pixel;
  FrameStats stats;
  const SpanImage gpu = test::voxelize(camera, p, o, {}, &stats);
  EXPECT_EQ(stats.count("tiles"), 4);
  for (int y = 0; y < gpu.height(); ++y)
    for (int x = 0; x < gpu.width(); ++x) ASSERT_GE(gpu.pixel(x, y).count, 1u) << x << "," << y;
  expect_matches_reference(gpu, p, 0);
  // Both splat thread layouts handle it.
  o.splat_threads = SplatThreads::per_particle;
  EXPECT_TRUE(test::identical(gpu, test::voxelize(camera, p, o)));
}

TEST(VoxelizeBadInput, ZeroParticlesAndNothingVisible) {
  const Camera camera = small_camera({0, 0, 5}, {0, 0, 0});
  FrameStats stats;
  const SpanImage none = test::voxelize(camera, {}, VoxelizeOptions{}, {}, &stats);
  EXPECT_TRUE(none.grid.empty());
  EXPECT_EQ(none.total_spans(), 0);
  EXPECT_EQ(none.pixels.size(), std::size_t(96 * 64));
  EXPECT_EQ(stats.count("particles.input"), 0);
  // Everything behind the camera or off to the side: the same empty image.
  const test::Particles unseen = {{0, 0, 8, 0.5f}, {50, 0, 0, 0.5f}};
  const SpanImage culled = test::voxelize(camera, unseen, VoxelizeOptions{}, {}, &stats);
  EXPECT_EQ(culled.total_spans(), 0);
  EXPECT_EQ(stats.count("particles.culled_behind"), 1);
  EXPECT_EQ(stats.count("particles.culled_outside"), 1);
}

TEST(VoxelizeBadInput, NaNAndNonPositiveRadiiAreCountedAndSkipped) {
  const Camera camera = small_camera({0, 0, 5}, {0, 0, 0});
  const test::Particles clean = test::random_cloud(300, {-1, -1, -1}, {1, 1, 1}, 0.02, 0.1, 5);
  test::Particles dirty = clean;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  dirty.insert(dirty.begin() + 7, {nan, 0, 0, 0.1f});
  dirty.insert(dirty.begin() + 50, {0, inf, 0, 0.1f});
  dirty.insert(dirty.begin() + 90, {0, 0, 0, nan});
  dirty.insert(dirty.begin() + 120, {0.1f, 0.1f, 0.1f, 0.0f});
  dirty.insert(dirty.begin() + 150, {0.1f, 0.1f, 0.1f, -1.0f});
  FrameStats stats;
  const SpanImage with = test::voxelize(camera, dirty, VoxelizeOptions{}, {}, &stats);
  EXPECT_EQ(stats.count("particles.invalid"), 5);
  EXPECT_TRUE(test::identical(with, test::voxelize(camera, clean, VoxelizeOptions{})));
}

TEST(VoxelizeBadInput, BudgetTooSmallForOneTileRowNamesTheBudgetNeeded) {
  const Camera camera = small_camera({0, 0, 5}, {0, 0, 0});
  const test::Particles p = test::random_cloud(100, {-1, -1, -1}, {1, 1, 1}, 0.02, 0.1, 6);
  VoxelizeOptions o;
  FrameStats stats;
  const SpanImage fine = test::voxelize(camera, p, o, {}, &stats);
  const std::size_t needed = 96 * ((std::size_t(fine.grid.layers()) + 127) / 128 * 16 +
                                   scratch_bytes_per_pixel(o.scratch_spans));
  o.tiles.memory_budget = needed - 1;
  try {
    test::voxelize(camera, p, o);
    FAIL() << "a budget below one tile row was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tile memory budget of " + std::to_string(needed - 1)), std::string::npos)
        << what;
    EXPECT_NE(what.find("at least " + std::to_string(needed) + " bytes"), std::string::npos)
        << what;
  }
  // Exactly one row per tile works, and gives the same spans.
  o.tiles.memory_budget = needed;
  EXPECT_TRUE(test::identical(fine, test::voxelize(camera, p, o, {}, &stats)));
  EXPECT_EQ(stats.count("tiles"), 64);
}

TEST(VoxelizeBadInput, OptionsOutOfRangeAreErrorsNamingTheOption) {
  const Camera camera = small_camera({0, 0, 5}, {0, 0, 0});
  const test::Particles p = test::one_sphere({0, 0, 0}, 0.5);
  const auto message = [&](VoxelizeOptions o, const Camera& c) -> std::string {
    try {
      test::voxelize(c, p, o);
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  VoxelizeOptions o;
  o.grid.alpha_degrees = 0;
  EXPECT_NE(message(o, camera).find("alpha_degrees"), std::string::npos);
  o = {};
  o.grid.max_layers = 100;
  EXPECT_NE(message(o, camera).find("max_layers"), std::string::npos);
  o = {};
  o.gap_bridging = -1;
  EXPECT_NE(message(o, camera).find("gap_bridging"), std::string::npos);
  o = {};
  o.gap_bridging = std::nan("");
  EXPECT_NE(message(o, camera).find("gap_bridging"), std::string::npos);
  Camera bad = camera;
  bad.target = bad.eye;
  EXPECT_NE(message({}, bad).find("eye equals its target"), std::string::npos);
  bad = camera;
  bad.width = 0;
  EXPECT_NE(message({}, bad).find("image size"), std::string::npos);
}

TEST(VoxelizeBadInput, LayerCapCoarsensTheSpacingAndSaysSo) {
  const Camera camera = small_camera({0, 0, 5}, {0, 0, 0});
  const test::Particles p = test::random_cloud(300, {-1, -1, -1}, {1, 1, 1}, 0.05, 0.15, 8);
  VoxelizeOptions o;
  o.grid.alpha_degrees = 1;
  o.grid.max_layers = 256;
  FrameStats stats;
  const SpanImage gpu = test::voxelize(camera, p, o, {}, &stats);
  EXPECT_EQ(stats.count("grid.layer_cap_hit"), 1);
  EXPECT_EQ(gpu.grid.layers(), 256);
  EXPECT_GT(stats.count("grid.layers_needed"), 256);
  EXPECT_GT(stats.figure("grid.alpha_degrees"), 1.0);
  // The 256 layers still span near to far, each within one (coarser) layer of the exact spans.
  EXPECT_NEAR(gpu.grid.grid_far(), gpu.grid.far(), 1e-6 * gpu.grid.far());
  const SpanImage ref = exact_spans(gpu.grid, p, {}, {});
  EXPECT_GE(test::compare_spans(gpu, ref).boundary_match(), 0.995);
}

}  // namespace
}  // namespace voxspan
