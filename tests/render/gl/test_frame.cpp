// The full frame and its parts that the other tests leave out: deep AO (occlusion near a step,
// none on a flat floor, the same behind a sheet that hides the occluder from a front-layer AO),
// the translucent 24-layer scene capped at 7 spans against uncapped, refraction resumed over
// many dispatches, Renderer::render from particles with its stats, and bad options.
#include <cmath>
#include <cstdio>

#include "render/gl/gpu_recorder.h"
#include "render/reference/reference_shading.h"
#include "tests/render/gl/render_fixture.h"
#include "tests/render/gl/shading_fixture.h"
#include "tools/scenes/image_compare.h"
#include "tools/scenes/scenes.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

// A floor at depth 5 over a 32 x 32 image; columns x < 12 hold a block raised 0.5 towards the
// eye; with `sheet`, they also hold a thin sheet at depth 2, in front of everything.
SpanImage step_scene(bool block, bool sheet) {
  std::vector<std::vector<Span>> columns(32 * 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      auto& c = columns[std::size_t(x) + 32 * std::size_t(y)];
      if (x < 12 && sheet) c.push_back({2.0f, 2.05f});
      c.push_back({x < 12 && block ? 4.5f : 5.0f, 6.0f});
    }
  return test::hand_made(32, 32, columns);
}

TEST(DeepAo, OccludedNextToAStepAndDeepBehindASheet) {
  ShadeOptions shade = test::test_shading(ShadeMode::opaque);
  shade.deep_ao = true;
  shade.ao.radius = 0.6;  // about five pixels at depth 5
  const std::vector<float> flat = test::shade_on_gpu(step_scene(false, false), {}, shade).ao;
  const std::vector<float> step = test::shade_on_gpu(step_scene(true, false), {}, shade).ao;
  const std::vector<float> hidden = test::shade_on_gpu(step_scene(true, true), {}, shade).ao;
  const auto at = [](const std::vector<float>& ao, int x, int y) {
    return ao[std::size_t(x) + 32 * std::size_t(y)];
  };
  for (int x = 2; x < 30; ++x) EXPECT_FLOAT_EQ(at(flat, x, 16), 1.0f) << "flat floor, x " << x;
  // On the floor right of the step: occluded near it, less so further away, not at all far off.
  EXPECT_LT(at(step, 12, 16), 0.9f);
  EXPECT_LT(at(step, 12, 16), at(step, 14, 16));
  EXPECT_FLOAT_EQ(at(step, 24, 16), 1.0f);
  // Deep: the sheet in front of the block hides it from the front layer, not from deep AO.
  for (int x = 12; x < 20; ++x) EXPECT_NEAR(at(hidden, x, 16), at(step, x, 16), 1e-6) << "x " << x;
  // And the opaque picture darkens where the AO says so.
  shade.deep_ao = false;
  const FloatImage plain = test::shade_on_gpu(step_scene(true, false), {}, shade).image;
  shade.deep_ao = true;
  const FloatImage with_ao = test::shade_on_gpu(step_scene(true, false), {}, shade).image;
  EXPECT_LT(with_ao.at(12, 16).g, plain.at(12, 16).g);
  EXPECT_FLOAT_EQ(with_ao.at(24, 16).g, plain.at(24, 16).g);
}

TEST(Translucency, TwentyFourLayersCappedAtSevenEqualUncapped) {
  const test::Particles layers = test::stacked_layers(24, 24, 2, 0.05, 0.045, 0.2);
  const Camera camera = test::look_at({0.62, 0.58, -1.2}, {0.6, 0.6, 1.0}, 128, 96);
  VoxelizeOptions options;
  options.gap_bridging = 0.025;
  options.max_spans = 7;
  const SpanImage capped = test::voxelize(camera, layers, options);
  options.max_spans = 0;
  const SpanImage all = test::voxelize(camera, layers, options);
  ASSERT_EQ(all.pixel(64, 48).count, 24u);
  ASSERT_EQ(capped.pixel(64, 48).count, 7u);
  ASSERT_GT(capped.capped_pixels(), 128 * 96 / 5);
  for (bool ao : {false, true}) {
    ShadeOptions shade = test::test_shading(ShadeMode::translucent);
    shade.deep_ao = ao;  // AO reads the front surface only: the cap cannot change it
    const test::ImageDifference d = test::compare_images(
        test::shade_on_gpu(capped, {}, shade).image, test::shade_on_gpu(all, {}, shade).image);
    std::printf("capped at 7 against all 24 spans (ao %d): max %d/255, PSNR %.1f dB\n", ao,
                d.max_levels, d.psnr);
    EXPECT_LE(d.max_levels, 1);
  }
}

TEST(Refraction, MarchesResumedOverManyDispatchesComplete) {
  // The dam break, and the 24 sheets seen edge-on at a slant (rays that cross every sheet
  // and march far across the image): each ray resumed every 3 events must end where one
  // marched in as few dispatches as the default budget allows, and every ray must finish.
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  const test::Particles dam = test::dam_break(shape, 0.3);
  const test::Particles sheets = test::stacked_layers(24, 24, 2, 0.05, 0.045, 0.2);
  VoxelizeOptions options;
  options.gap_bridging = shape.spacing;
  for (const test::Particles* particles : {&dam, &sheets}) {
    const SpanImage spans = test::voxelize(test::frame_scene(*particles, {0.4, -0.5, -1}, 256, 144),
                                           *particles, options);
    ShadeOptions shade = test::test_shading(ShadeMode::refractive);
    shade.bounces = 8;
    shade.environment.ground_height = -1e3;  // far below: no ray ends on it early
    const test::GpuResult whole = test::shade_on_gpu(spans, {}, shade);
    shade.march_budget = 3;  // a few column events per ray and dispatch
    const test::GpuResult pieces = test::shade_on_gpu(spans, {}, shade);
    std::printf(
        "default budget: %lld dispatches, longest ray %lld events; budget 3: %lld dispatches\n",
        static_cast<long long>(whole.stats.count("refract.dispatches")),
        static_cast<long long>(whole.stats.count("refract.most_events")),
        static_cast<long long>(pieces.stats.count("refract.dispatches")));
    EXPECT_EQ(whole.stats.count("refract.unfinished"), 0);
    EXPECT_EQ(pieces.stats.count("refract.unfinished"), 0);
    EXPECT_GT(whole.stats.count("refract.most_events"), 150) << "rays should cross many columns";
    EXPECT_EQ(pieces.stats.count("refract.events"), whole.stats.count("refract.events"));
    EXPECT_EQ(pieces.image.rgba, whole.image.rgba) << "resuming a ray must not change its path";
  }
}

TEST(Refraction, AMarchLongerThanOneDispatchCompletes) {
  // 700 thin spans in every column: the centre rays cross 1400 boundaries, more than one
  // dispatch's default budget of column events, whose loops llvmpipe would cut short
  // silently past 65535 iterations if a dispatch tried them all. The GPU must agree with the
  // CPU (no loop limit) and with itself resumed every 7 events.
  std::vector<Span> column;
  for (int k = 0; k < 700; ++k) column.push_back({2.0f + 0.01f * k, 2.005f + 0.01f * k});
  const SpanImage spans =
      test::hand_made(8, 8, std::vector<std::vector<Span>>(64, column), 1.0, 12.0);
  ShadeOptions shade = test::test_shading(ShadeMode::refractive);
  shade.material.absorption = {0.2, 0.1, 0.05};
  shade.environment.ground_height = -1e3;  // the eye is at height 0: keep the ground off its rays
  const test::GpuResult gpu = test::shade_on_gpu(spans, {}, shade);
  EXPECT_GT(gpu.stats.count("refract.events"), 64 * 1400);
  EXPECT_GE(gpu.stats.count("refract.dispatches"), 2);
  EXPECT_EQ(gpu.stats.count("refract.unfinished"), 0);
  const FloatImage cpu = reference_shading(spans, shade);
  EXPECT_LE(test::compare_images(gpu.image, cpu).max_levels, 1);
  shade.march_budget = 7;
  EXPECT_EQ(test::shade_on_gpu(spans, {}, shade).image.rgba, gpu.image.rgba);
  // Through 700 x 0.005 of fluid, red absorbed most: redder without the fluid, not black with it.
  const FloatImage empty =
      test::shade_on_gpu(test::hand_made(8, 8, std::vector<std::vector<Span>>(64), 1.0, 12.0), {},
                         shade)
          .image;
  EXPECT_LT(gpu.image.at(4, 4).r, 0.95f * empty.at(4, 4).r);
  EXPECT_GT(gpu.image.at(4, 4).r, 0.05f);
}

TEST(Refraction, WaterRestingOnTheGroundShowsTheGroundThroughIt) {
  // A layer three particles thick on the ground (y = 0, its lowest particles half a spacing
  // above it), its top particles jittered so that the free surface tilts this way and that,
  // seen from above at 35 degrees: rays enter through the tilted top and reach the bottom past
  // the critical angle. Were the union's bottom a water-air surface, they would reflect totally
  // and run on inside the layer, gathering scattered light (blue speckles: the refraction's
  // speckles of the dam break's thin surge). Resting on the opaque ground, every ray ends on it,
  // through a few spacings of water: no pixel gathers more than that much scattering.
  const double s = 0.01;
  test::Particles layer = test::lattice_block({-0.3, 0, -0.3}, {60, 3, 60}, s, float(s));
  std::uint32_t seed = 7;
  for (ParticleSphere& p : layer)
    if (p.y > 2 * s) {
      seed = seed * 1664525u + 1013904223u;
      p.y += float(s * 0.6 * (double(seed >> 8) / double(1u << 24) - 0.5));
    }
  const Camera camera = test::look_at({0, 0.35, -0.5}, {0, 0, 0}, 160, 96, 40);
  VoxelizeOptions options;
  options.gap_bridging = s;
  const SpanImage spans = test::voxelize(camera, layer, options);
  ShadeOptions shade = test::test_shading(ShadeMode::refractive, 0.12);
  shade.material.absorption = {2, 2, 2};     // per unit: a few percent over the layer
  shade.material.scatter_color = {0, 0, 1};  // scattering shows as blue over red
  shade.environment.rest_on_floor(0, s);
  auto most_blue = [&](const ShadeOptions& o, int* bluer_than) {
    const FloatImage image = test::shade_on_gpu(spans, {}, o).image;
    float most = 0;
    *bluer_than = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const glm::vec4 c = image.at(x, y);
        most = std::max(most, c.b - c.r);
        if (c.b - c.r > 0.2f) ++*bluer_than;
      }
    return most;
  };
  int resting = 0, floating = 0;
  const float most = most_blue(shade, &resting);
  ShadeOptions apart = shade;  // the ground under the union's bottom, no contact: the old rule
  apart.environment.ground_height = -0.5 * s;
  apart.environment.ground_contact = 0;
  const float most_apart = most_blue(apart, &floating);
  std::printf(
      "blue over red: at most %.3f resting on the ground, %.3f apart (%d pixels over 0.2)\n", most,
      most_apart, floating);
  EXPECT_EQ(resting, 0);
  EXPECT_LT(most, 0.2f);
  EXPECT_GT(floating, 0) << "the scene should show the totally reflected rays without the contact";
}

TEST(Renderer, FullFrameFromParticles) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  const test::Particles dam = test::dam_break(shape, 0.2);
  const Camera camera = test::frame_scene(dam, {0.4, -0.5, -1}, 160, 90);
  RenderOptions options;
  options.voxelize.gap_bridging = shape.spacing;
  options.surfaces.filter_radius = shape.spacing;
  for (ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive}) {
    options.shade = test::test_shading(mode);
    options.shade.deep_ao = true;
    FrameStats stats;
    gl::GpuRecorder recorder(stats, test::context().has_gpu_timers());
    const FloatImage image = test::renderer().render(camera, dam, {}, options, recorder).download();
    recorder.collect();
    for (const char* pass :
         {"splat", "compress", "connect", "filter", "normals", "deep_ao", "shade"})
      EXPECT_EQ(stats.runs(pass) > 0, true) << pass;
    EXPECT_GT(stats.count("filter.iterations"), 0);
    // Against the same spans shaded by the passes alone (the render() path adds nothing else).
    const SpanImage spans = test::voxelize(camera, dam, options.voxelize);
    const test::ImageDifference d = test::compare_images(
        image, test::shade_on_gpu(spans, options.surfaces, options.shade).image);
    EXPECT_EQ(d.max_levels, 0) << shade_mode_name(mode);
  }
}

TEST(Renderer, NoParticlesGiveTheEnvironment) {
  const Camera camera = test::look_at({0, 1, 3}, {0, 0, 0}, 32, 24);
  for (ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive}) {
    RenderOptions options;
    options.shade = test::test_shading(mode);
    options.shade.deep_ao = true;
    options.surfaces.filter_radius = 0.1;
    gl::GpuRecorder recorder(false);
    const FloatImage image = test::renderer().render(camera, {}, {}, options, recorder).download();
    ASSERT_EQ(image.width, 32);
    // Sky at the top, ground at the bottom, nothing else.
    EXPECT_GT(image.at(16, 0).b, image.at(16, 0).r) << shade_mode_name(mode);
    for (float c : image.rgba) ASSERT_TRUE(std::isfinite(c));
  }
}

TEST(Renderer, BadOptionsNameTheOption) {
  RenderOptions options;
  const auto message = [&] {
    gl::GpuRecorder recorder(false);
    try {
      test::renderer().render(test::look_at({0, 0, 3}, {0, 0, 0}, 8, 8),
                              test::one_sphere({0, 0, 0}, 1), {}, options, recorder);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  options.surfaces.filter_radius = -1;
  EXPECT_NE(message().find("filter_radius"), std::string::npos) << message();
  options = {};
  options.shade.material.ior = 0.5;
  EXPECT_NE(message().find("ior"), std::string::npos) << message();
  options = {};
  options.shade.ao.samples = 0;
  EXPECT_NE(message().find("ao samples"), std::string::npos) << message();
  options = {};
  options.shade.material.absorption = {0, -1, 0};
  EXPECT_NE(message().find("absorption"), std::string::npos) << message();
  options = {};
  options.shade.environment.up = {0, 0, 0};
  EXPECT_NE(message().find("up"), std::string::npos) << message();
  options = {};
  options.shade.march_budget = 0;
  EXPECT_NE(message().find("march_budget"), std::string::npos) << message();
  options = {};
  EXPECT_EQ(message(), "no error");
}

}  // namespace
}  // namespace voxspan
