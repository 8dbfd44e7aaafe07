// The CPU renderer (render/cpu/cpu_renderer.h) against the exact reference and the GPU:
//   - its spans are the exact reference's on the accuracy scenes and on the dam break with
//     inner-full cells, within float rounding (stated in layers of the GPU's grid and in
//     particle radii);
//   - its pictures, filter off, are within the GPU's PSNR bounds against the reference with
//     the same normals (tests/render/gl/test_shade_accuracy.cpp), mode by mode;
//   - on one span image, its filter, normals and shading are the GPU passes' (the same model
//     files), filter on;
//   - the same pictures whatever the number of threads, and whether the background behind the
//     pixels was kept from the frames before (a steady camera) or computed.
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>

#include "render/cpu/cpu_renderer.h"
#include "render/reference/exact_spans.h"
#include "render/reference/reference_shading.h"
#include "tests/render/gl/render_fixture.h"
#include "tests/render/gl/shading_fixture.h"
#include "tools/scenes/accuracy_scenes.h"
#include "tools/scenes/image_compare.h"
#include "tools/scenes/scene_cell_states.h"
#include "tools/scenes/scenes.h"

namespace voxspan {
namespace {

// The largest difference of a boundary between two span images with the same counts, in
// layers of `a`'s grid and in world units; false when any pixel's counts differ.
struct SpanDifference {
  bool counts_equal = true;
  double layers = 0, world = 0;
  std::int64_t spans = 0;
};

SpanDifference difference(const SpanImage& a, const SpanImage& b) {
  SpanDifference d;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const PixelSpans& p = a.pixel(x, y);
      const PixelSpans& q = b.pixel(x, y);
      if (p.count != q.count || p.total != q.total) {
        d.counts_equal = false;
        continue;
      }
      for (std::uint32_t k = 0; k < p.count; ++k) {
        const Span s = a.spans[p.offset + k], t = b.spans[q.offset + k];
        for (const auto& [u, v] : {std::pair{s.entry, t.entry}, std::pair{s.exit, t.exit}}) {
          const double e = std::abs(double(u) - double(v));
          d.world = std::max(d.world, e);
          d.layers = std::max(d.layers, e / a.grid.layer_thickness(u));
        }
        ++d.spans;
      }
    }
  return d;
}

TEST(CpuRenderer, SpansAreTheExactReferencesOnTheAccuracyScenes) {
  for (const test::AccuracyScene& scene : test::accuracy_scenes(160, 120)) {
    SCOPED_TRACE(scene.name);
    CpuRenderer cpu;
    FrameStats stats;
    Recorder recorder(stats);
    const SpanImage& spans = cpu.cast(scene.camera, scene.particles, {}, scene.options, recorder);
    const SpanImage exact = exact_spans(spans.grid, scene.particles, {},
                                        {scene.options.gap_bridging, scene.options.max_spans});
    const SpanDifference d = difference(spans, exact);
    const double radius = scene.particles.front().radius;
    std::printf("%-18s %lld spans, largest difference %.2g layers, %.2g radii\n",
                scene.name.c_str(), static_cast<long long>(d.spans), d.layers, d.world / radius);
    EXPECT_TRUE(d.counts_equal);
    EXPECT_GT(d.spans, 0);
    EXPECT_LE(d.layers, 1e-3);
    EXPECT_EQ(stats.count("spans.found"), exact.total_spans());
  }
}

TEST(CpuRenderer, SpansWithInnerFullCellsAreTheExactReferences) {
  test::DamBreak shape;
  shape.spacing = 0.01;
  shape.radius = 0.01;
  for (double t : {0.0, 0.3}) {
    SCOPED_TRACE(t);
    const test::Particles all = test::dam_break(shape, t);
    const test::TestCells cells = test::classify_for_test(all, 2 * shape.spacing, 8);
    ASSERT_GT(cells.inner_full_cells, 0);
    VoxelizeOptions options;
    options.gap_bridging = shape.spacing;
    const Camera camera = test::frame_scene(all, {0.4, -0.5, -1}, 192, 108);
    CpuRenderer cpu;
    FrameStats stats;
    Recorder recorder(stats);
    const SpanImage& spans = cpu.cast(camera, cells.boundary, cells.view, options, recorder);
    const SpanImage exact =
        exact_spans(spans.grid, cells.boundary, cells.view, {options.gap_bridging, 0});
    const SpanDifference d = difference(spans, exact);
    std::printf(
        "dam break t=%.1f: %lld spans, %lld cell boxes, largest difference %.2g layers, "
        "%.2g radii\n",
        t, static_cast<long long>(d.spans), static_cast<long long>(stats.count("cast.cell_boxes")),
        d.layers, d.world / shape.radius);
    EXPECT_TRUE(d.counts_equal);
    EXPECT_GT(stats.count("cast.cell_boxes"), 0);
    EXPECT_LE(d.layers, 1e-3);
  }
}

TEST(CpuRenderer, PicturesAreWithinTheGpusBoundsAgainstTheReference) {
  for (const test::AccuracyScene& scene : test::accuracy_scenes(160, 120)) {
    SCOPED_TRACE(scene.name);
    CpuRenderer cpu;
    FrameStats stats;
    Recorder recorder(stats);
    const SpanImage spans = cpu.cast(scene.camera, scene.particles, {}, scene.options, recorder);
    const SpanImage exact = exact_spans(spans.grid, scene.particles, {},
                                        {scene.options.gap_bridging, scene.options.max_spans});
    const std::vector<glm::uvec2> sobel = reference_normals(exact, reference_links(exact));
    const SpanImage voxelized = test::voxelize(scene.camera, scene.particles, scene.options);
    for (ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive}) {
      SCOPED_TRACE(shade_mode_name(mode));
      const ShadeOptions shade = test::test_shading(mode, scene.ground_tile);
      const FloatImage& image = cpu.shade(spans, {}, shade, recorder);
      const double psnr = test::compare_images(image, reference_shading(exact, shade, &sobel)).psnr;
      const double gpu =
          test::compare_images(test::shade_on_gpu(voxelized, {}, shade).image, image).psnr;
      std::printf("%-18s %-12s PSNR %5.1f dB against the reference, %5.1f dB against the GPU\n",
                  scene.name.c_str(), shade_mode_name(mode), psnr, gpu);
      const bool stack = scene.name.rfind("24 layers", 0) == 0;
      EXPECT_GE(psnr, mode != ShadeMode::refractive ? 32.0 : (stack ? 22.0 : 26.0));
    }
  }
}

TEST(CpuRenderer, FilterNormalsAndShadingAreTheGpuPassesOnOneSpanImage) {
  const test::AccuracyScene scene = test::accuracy_scenes(160, 120).front();
  const SpanImage spans = test::voxelize(scene.camera, scene.particles, scene.options);
  SurfaceOptions filter;
  filter.filter_radius = 2 * scene.particles.front().radius;
  filter.fold_step = 2.5 * scene.particles.front().radius;  // as the views set it
  CpuRenderer cpu;
  for (ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive}) {
    SCOPED_TRACE(shade_mode_name(mode));
    ShadeOptions shade = test::test_shading(mode, scene.ground_tile);
    shade.deep_ao = mode == ShadeMode::translucent;
    FrameStats stats;
    Recorder recorder(stats);
    const FloatImage& image = cpu.shade(spans, filter, shade, recorder);
    const test::GpuResult gpu = test::shade_on_gpu(spans, filter, shade);
    ASSERT_GT(gpu.stats.count("filter.iterations"), 1);
    EXPECT_EQ(stats.count("filter.iterations"), gpu.stats.count("filter.iterations"));
    const test::ImageDifference d = test::compare_images(image, gpu.image);
    std::printf("%-12s filter %lld iterations: PSNR %5.1f dB against the GPU, at most %d/255\n",
                shade_mode_name(mode), static_cast<long long>(stats.count("filter.iterations")),
                d.psnr, d.max_levels);
    EXPECT_GE(d.psnr, mode == ShadeMode::refractive ? 35.0 : 45.0);
  }
}

// A small dam break (cells of two spacings) and the renderer's picture of it.
struct SmallDamBreak {
  test::DamBreak shape = [] {
    test::DamBreak d;
    d.spacing = 0.01;
    d.radius = 0.01;
    return d;
  }();
  test::Particles all = test::dam_break(shape, 0.3);
  test::TestCells cells = test::classify_for_test(all, 2 * shape.spacing, 8);

  Camera camera(glm::dvec3 direction) const { return test::frame_scene(all, direction, 160, 90); }
  std::vector<float> render(CpuRenderer& cpu, const Camera& camera, const SurfaceOptions& filter,
                            const ShadeOptions& shade) const {
    VoxelizeOptions options;
    options.gap_bridging = shape.spacing;
    FrameStats stats;
    Recorder recorder(stats);
    const SpanImage& spans = cpu.cast(camera, cells.boundary, cells.view, options, recorder);
    return cpu.shade(spans, filter, shade, recorder).rgba;
  }
};

TEST(CpuRenderer, ThePicturesDoNotDependOnTheThreads) {
  const SmallDamBreak scene;
  SurfaceOptions filter;
  filter.filter_radius = scene.shape.spacing;
  const Camera camera = scene.camera({0.4, -0.5, -1});
  const auto render = [&](int threads, ShadeMode mode) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    CpuRenderer cpu;
    ShadeOptions shade = test::test_shading(mode);
    shade.deep_ao = true;
    return scene.render(cpu, camera, filter, shade);
  };
  for (ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive}) {
    SCOPED_TRACE(shade_mode_name(mode));
    const std::vector<float> one = render(1, mode);
    EXPECT_EQ(one, render(3, mode));
    EXPECT_EQ(one, render(8, mode));
  }
}

TEST(CpuRenderer, TheBackgroundKeptWhileTheCameraStaysIsTheOneComputed) {
  const SmallDamBreak scene;
  const Camera front = scene.camera({0.4, -0.5, -1}), side = scene.camera({-1, -0.4, -0.3});
  for (ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent}) {
    SCOPED_TRACE(shade_mode_name(mode));
    const ShadeOptions shade = test::test_shading(mode);
    ShadeOptions evening = shade;
    evening.environment.sun_direction = {-0.8, 0.3, 0.2};
    // Each frame of one renderer against a new renderer's first frame (nothing kept).
    CpuRenderer kept;
    const struct {
      const Camera& camera;
      const ShadeOptions& shade;
    } frames[] = {{front, shade}, {front, shade},  {front, shade},  {side, shade},
                  {side, shade},  {side, evening}, {side, evening}, {front, shade}};
    int frame = 0;
    for (const auto& f : frames) {
      SCOPED_TRACE(frame++);
      CpuRenderer fresh;
      EXPECT_EQ(scene.render(kept, f.camera, {}, f.shade),
                scene.render(fresh, f.camera, {}, f.shade));
    }
  }
}

}  // namespace
}  // namespace voxspan
