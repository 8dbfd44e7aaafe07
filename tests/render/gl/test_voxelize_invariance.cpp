// The span image does not depend on how the work is cut up: the same spans, bit for bit,
// whatever the tile size (bands, 2D tiles, more tiles than the binning's shared tallies hold),
// the order of the particles, the binning (per-tile lists, tallied in shared memory or not, or
// the paper's re-splat of all particles), the splat's threads (per pixel or per particle),
// surface-only or whole-chord marking under gap bridging, and the compress scratch size (copy or
// re-scan).
#include <algorithm>
#include <random>

#include "tests/render/gl/render_fixture.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/span_compare.h"

namespace voxspan {
namespace {

struct Scene {
  test::Particles particles;
  Camera camera;
  VoxelizeOptions options;
};

Scene dam_break_scene(int width, int height) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  shape.spray_fraction = 0.01;
  Scene s{test::dam_break(shape, 0.3), {}, {}};
  // Droplets all over the tank, so that many rays cross more spans than the cap.
  const test::Particles drops = test::random_cloud(400, {0, 0, 0}, {1.2, 0.6, 0.3}, 0.005, 0.03, 9);
  s.particles.insert(s.particles.end(), drops.begin(), drops.end());
  s.camera = test::frame_scene(s.particles, {0.4, -0.5, -1}, width, height);
  s.options.grid.alpha_degrees = 4;
  s.options.gap_bridging = 2.5 * shape.spacing;  // above a diameter: surface-only marking is on
  s.options.max_spans = 2;
  s.options.splat_threads = SplatThreads::per_pixel;  // the other layout is a variant below
  return s;
}

void expect_identical(const SpanImage& a, const SpanImage& b, const char* what) {
  EXPECT_TRUE(test::identical(a, b)) << what << ": " << test::compare_spans(b, a).summary();
}

TEST(VoxelizeInvariance, SameSpansWhateverTilesOrderBinningThreadsAndMarking) {
  const Scene s = dam_break_scene(160, 96);
  FrameStats stats;
  const SpanImage base = test::voxelize(s.camera, s.particles, s.options, {}, &stats);
  ASSERT_EQ(stats.count("tiles"), 1);
  ASSERT_GT(base.capped_pixels(), 0) << "the cap must bite for the test to cover it";
  ASSERT_GT(base.total_spans(), 1000);

  test::Particles shuffled = s.particles;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(3));
  test::Particles reversed(s.particles.rbegin(), s.particles.rend());

  VoxelizeOptions o = s.options;
  // Bands of a few rows: the budget allows 7 rows of bits and scratch.
  const std::size_t row = 160 * (base.grid.layers() / 128 + 1) * 16 + 160 * (8 * 8 + 8);
  o.tiles.memory_budget = 7 * row;
  FrameStats band_stats;
  expect_identical(base, test::voxelize(s.camera, shuffled, o, {}, &band_stats),
                   "7-row bands, shuffled");
  EXPECT_GE(band_stats.count("tiles"), 96 / 7);

  o = s.options;
  o.tiles.max_width = 37;
  o.tiles.max_height = 13;
  expect_identical(base, test::voxelize(s.camera, reversed, o), "37x13 tiles, reversed");

  o.binning = Binning::resplat_all;
  expect_identical(base, test::voxelize(s.camera, s.particles, o), "re-splat all, 37x13 tiles");

  o = s.options;
  o.splat_threads = SplatThreads::per_particle;
  expect_identical(base, test::voxelize(s.camera, shuffled, o), "one thread per particle");

  for (BinTallies tallies : {BinTallies::shared, BinTallies::global}) {
    o = s.options;
    o.tiles.max_width = 37;
    o.bin_tallies = tallies;
    expect_identical(base, test::voxelize(s.camera, s.particles, o),
                     tallies == BinTallies::shared ? "shared tallies" : "global tallies");
  }

  o = s.options;
  o.surface_splat = false;
  expect_identical(base, test::voxelize(s.camera, s.particles, o), "whole chords");

  o = s.options;
  o.scratch_spans = 1;  // every capped pixel is scanned again by the write pass
  expect_identical(base, test::voxelize(s.camera, s.particles, o), "one scratch span");

  // The comparison can fail: a smaller gap changes the spans.
  o = s.options;
  o.gap_bridging = 0.5 * s.options.gap_bridging;
  EXPECT_FALSE(test::identical(base, test::voxelize(s.camera, s.particles, o)));
}

TEST(VoxelizeInvariance, MoreTilesThanTheSharedTalliesHold) {
  const Scene s = dam_break_scene(64, 48);
  const SpanImage base = test::voxelize(s.camera, s.particles, s.options);
  VoxelizeOptions o = s.options;
  o.tiles.max_width = 2;
  o.tiles.max_height = 1;  // 32 x 48 = 1536 tiles: the binning's global-atomic path
  FrameStats stats;
  expect_identical(base, test::voxelize(s.camera, s.particles, o, {}, &stats), "1536 tiles");
  EXPECT_EQ(stats.count("tiles"), 1536);
}

}  // namespace
}  // namespace voxspan
