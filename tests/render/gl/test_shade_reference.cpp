// The GPU passes against the CPU reference's compilation of the same model files on the same
// spans: links, normals, deep AO and every shading mode agree up to float rounding, so any
// difference between the GPU's picture and the exact reference's comes from the spans alone.
#include <cstdio>

#include "render/reference/reference_shading.h"
#include "tests/render/gl/render_fixture.h"
#include "tests/render/gl/shading_fixture.h"
#include "tools/scenes/image_compare.h"
#include "tools/scenes/scenes.h"

namespace voxspan {
namespace {

SpanImage dam_break_spans(int width, int height) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  const test::Particles dam = test::dam_break(shape, 0.25);
  VoxelizeOptions options;
  options.gap_bridging = 0.02;
  const Camera camera = test::frame_scene(dam, {0.5, -0.45, -1}, width, height);
  return test::voxelize(camera, dam, options);
}

TEST(ShadeReference, NormalsAndAoMatchTheCpu) {
  const SpanImage spans = dam_break_spans(160, 96);
  ShadeOptions shade = test::test_shading(ShadeMode::opaque);
  shade.deep_ao = true;
  const test::GpuResult gpu = test::shade_on_gpu(spans, {}, shade);
  const std::vector<glm::uvec2> links = reference_links(spans);
  const std::vector<glm::uvec2> normals = reference_normals(spans, links);
  ASSERT_EQ(normals.size(), gpu.normals.size());
  double worst = 0;
  std::size_t equal = 0;
  for (std::size_t s = 0; s < normals.size(); ++s) {
    equal += normals[s] == gpu.normals[s];
    for (int end = 0; end < 2; ++end) {
      const glm::vec2 a = glm::unpackSnorm2x16(end == 0 ? normals[s].x : normals[s].y);
      const glm::vec2 b = glm::unpackSnorm2x16(end == 0 ? gpu.normals[s].x : gpu.normals[s].y);
      worst = std::max(worst, double(glm::length(a - b)));
    }
  }
  std::printf("normal words equal on %zu of %zu spans, worst octahedral distance %.2e\n", equal,
              normals.size(), worst);
  EXPECT_LT(worst, 1e-3);
  const std::vector<float> ao = reference_ao(spans, links, normals, shade);
  double ao_worst = 0;
  for (std::size_t p = 0; p < ao.size(); ++p)
    ao_worst = std::max(ao_worst, double(std::abs(ao[p] - gpu.ao[p])));
  std::printf("deep AO: worst difference %.2e\n", ao_worst);
  EXPECT_LT(ao_worst, 2e-3);
}

TEST(ShadeReference, EveryModeMatchesTheCpu) {
  const SpanImage spans = dam_break_spans(160, 96);
  for (ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive}) {
    for (bool ao : {false, true}) {
      ShadeOptions shade = test::test_shading(mode);
      shade.deep_ao = ao;
      const test::GpuResult gpu = test::shade_on_gpu(spans, {}, shade);
      const FloatImage cpu = reference_shading(spans, shade);
      const test::ImageDifference d = test::compare_images(gpu.image, cpu);
      std::printf("%-12s ao %d: PSNR %.1f dB, max %d/255, mean %.4f/255\n", shade_mode_name(mode),
                  ao, d.psnr, d.max_levels, d.mean_levels);
      SCOPED_TRACE(shade_mode_name(mode));
      // Refraction follows each ray through many columns: a rounding difference can tip a
      // grazing ray into another column, so a few pixels may differ more.
      EXPECT_GE(d.psnr, mode == ShadeMode::refractive ? 50.0 : 55.0);
      if (mode != ShadeMode::refractive) {
        EXPECT_LE(d.max_levels, 2);
      }
    }
  }
}

}  // namespace
}  // namespace voxspan
