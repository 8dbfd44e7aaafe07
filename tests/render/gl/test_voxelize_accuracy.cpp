// The GPU's span images against the exact CPU reference on the scenes: one sphere, a
// lattice block, the dam break at a few steps, 24 stacked layers with a cap of 7, a 3D
// checkerboard, random clouds with mixed radii. Bounds (in local layer thicknesses): span
// counts equal on >= 99.5 % of hit pixels, boundaries within one layer for >= 99.5 %, inside
// length per pixel within one layer per boundary, and summed over the image within 1 %.
#include "render/gl/bindings.h"
#include "render/gl/uniforms.h"
#include "render/reference/exact_spans.h"
#include "tests/render/gl/render_fixture.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/span_compare.h"

namespace voxspan {
namespace {

struct Case {
  test::Particles particles;
  Camera camera;
  VoxelizeOptions options;
};

test::SpanComparison check(const Case& c, const char* name) {
  FrameStats stats;
  const SpanImage gpu = test::voxelize(c.camera, c.particles, c.options, {}, &stats);
  const SpanImage ref =
      exact_spans(gpu.grid, c.particles, {}, {c.options.gap_bridging, c.options.max_spans});
  const test::SpanComparison cmp = test::compare_spans(gpu, ref);
  SCOPED_TRACE(name);
  EXPECT_GT(cmp.pixels_hit, 0);
  EXPECT_GE(cmp.count_match(), 0.995) << cmp.summary() << test::describe_mismatches(gpu, ref, 6);
  EXPECT_GE(cmp.boundary_match(), 0.995) << cmp.summary();
  EXPECT_GE(cmp.inside_match(), 0.995) << cmp.summary();
  EXPECT_LE(cmp.inside_sum_error(), 0.01) << cmp.summary();
  std::printf("[%s] %d layers: %s\n", name, gpu.grid.layers(), cmp.summary().c_str());
  return cmp;
}

TEST(VoxelizeAccuracy, OneSphere) {
  Case c{test::one_sphere({0.1, -0.05, 0.2}, 0.5), {}, {}};
  c.camera = test::frame_scene(c.particles, {0.3, -0.2, -1}, 128, 96);
  c.options.grid.alpha_degrees = 2;  // a few thousand layers
  const auto cmp = check(c, "one sphere");
  EXPECT_EQ(cmp.count_match(), 1.0);
  EXPECT_EQ(cmp.boundary_match(), 1.0);
}

TEST(VoxelizeAccuracy, LatticeBlock) {
  Case c{test::lattice_block({0, 0, 0}, {12, 10, 8}, 0.1, 0.09), {}, {}};
  c.camera = test::frame_scene(c.particles, {0.5, -0.4, -1}, 160, 120);
  c.options.grid.alpha_degrees = 2;
  check(c, "lattice block");
}

TEST(VoxelizeAccuracy, DamBreakAtThreeSteps) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  for (double t : {0.0, 0.15, 0.3}) {
    Case c{test::dam_break(shape, t), {}, {}};
    c.camera = test::frame_scene(c.particles, {0.4, -0.5, -1}, 192, 108);
    c.options.gap_bridging = shape.spacing;
    c.options.grid.alpha_degrees = 2;
    check(c, t == 0 ? "dam break t=0" : (t < 0.2 ? "dam break t=0.15" : "dam break t=0.3"));
  }
}

// Span ends at the end voxels' centres (VoxelizeOptions::span_edges): within half a layer of the
// exact boundaries where faces are within one, the inside length no longer a voxel long per
// span, and ends clipped by the near plane still at it.
TEST(VoxelizeAccuracy, SpanEndsAtVoxelCentresAreWithinHalfALayer) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  Case c{test::dam_break(shape, 0.15), {}, {}};
  c.camera = test::frame_scene(c.particles, {0.4, -0.5, -1}, 192, 108);
  c.options.gap_bridging = shape.spacing;
  c.options.grid.alpha_degrees = 2;
  const test::SpanComparison faces = check(c, "dam break, ends at faces");
  c.options.span_edges = SpanEdges::middle;
  const test::SpanComparison centres = check(c, "dam break, ends at centres");
  c.options.span_edges = SpanEdges::outer;
  const SpanImage at_faces = test::voxelize(c.camera, c.particles, c.options);
  c.options.span_edges = SpanEdges::middle;
  const SpanImage at_centres = test::voxelize(c.camera, c.particles, c.options);
  const SpanImage ref = exact_spans(at_centres.grid, c.particles, {}, {c.options.gap_bridging, 0});
  const double half_faces = test::compare_spans(at_faces, ref, 0.5).boundary_match();
  const double half_centres = test::compare_spans(at_centres, ref, 0.5).boundary_match();
  std::printf("boundaries within half a layer: faces %.4f, centres %.4f\n", half_faces,
              half_centres);
  EXPECT_GE(half_centres, 0.995);
  EXPECT_LT(half_faces, half_centres);
  EXPECT_LT(std::abs(centres.inside_sum_error()), std::abs(faces.inside_sum_error()) / 2)
      << "faces " << faces.summary() << "\ncentres " << centres.summary();
  const Camera inside = test::look_at({0.15, 0.3, 0.15}, {1.0, 0.25, 0.2}, 96, 64);
  const SpanImage from_inside = test::voxelize(inside, test::dam_break(shape, 0.0), c.options);
  for (int y = 0; y < from_inside.height(); ++y)
    for (int x = 0; x < from_inside.width(); ++x)
      ASSERT_EQ(from_inside.spans_at(x, y)[0].entry, float(from_inside.grid.near()))
          << x << "," << y;
}

TEST(VoxelizeAccuracy, TwentyFourLayersCappedAtSeven) {
  // Sheets two spheres thick, 0.2 apart along the view direction, filling the image.
  Case c{test::stacked_layers(24, 24, 2, 0.05, 0.045, 0.2), {}, {}};
  c.camera = test::look_at({0.62, 0.58, -1.2}, {0.6, 0.6, 1.0}, 128, 96);
  c.options.max_spans = 7;
  c.options.gap_bridging = 0.025;
  c.options.grid.alpha_degrees = 1;
  check(c, "24 layers, cap 7");
  // The central rays cross all 24 sheets: 7 spans stored, 24 found.
  const SpanImage gpu = test::voxelize(c.camera, c.particles, c.options);
  const PixelSpans& centre = gpu.pixel(gpu.width() / 2, gpu.height() / 2);
  EXPECT_EQ(centre.count, 7u);
  EXPECT_EQ(centre.total, 24u);
  EXPECT_GT(gpu.capped_pixels(), gpu.width() * gpu.height() / 5);

  // Later passes read the same image on the GPU (render/gl/span_image.glsl): the capped gap
  // length there agrees with the CPU's, and stored lengths minus the gap give `inside`.
  const GpuSpanImage& image = test::voxelizer().image();
  gl::Buffer probe(std::size_t(gpu.width()) * gpu.height() * 8);
  gl::Program program = test::shaders().compute("tests/render/gl/span_image_probe.comp",
                                                binding::span_image_defines());
  set_grid_uniforms(program, image.grid());
  image.bind();
  probe.bind(GL_SHADER_STORAGE_BUFFER, 2);
  program.dispatch(static_cast<GLuint>((gpu.width() * gpu.height() + 63) / 64));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const auto got = probe.read<glm::vec2>(std::size_t(gpu.width()) * gpu.height());
  for (int y = 0; y < gpu.height(); ++y)
    for (int x = 0; x < gpu.width(); ++x) {
      const glm::vec2 g = got[std::size_t(x) + std::size_t(y) * gpu.width()];
      const double cpu = gpu.capped_gap_length(x, y);
      ASSERT_NEAR(g.x, cpu, 1e-4 * (1 + cpu)) << x << "," << y;
      ASSERT_NEAR(g.y - g.x, gpu.pixel(x, y).inside, 1e-4 * (1 + g.y)) << x << "," << y;
    }
}

TEST(VoxelizeAccuracy, Checkerboard) {
  Case c{test::checkerboard(6, 4, 0.05, 0.045), {}, {}};
  c.camera = test::frame_scene(c.particles, {0.6, -0.5, -1}, 160, 120);
  c.options.max_spans = 7;
  c.options.gap_bridging = 0.025;
  c.options.grid.alpha_degrees = 2;
  check(c, "checkerboard");
}

TEST(VoxelizeAccuracy, RandomCloudsMixedRadii) {
  for (std::uint32_t seed : {1u, 2u}) {
    Case c{test::random_cloud(400, {0, 0, 0}, {1, 1, 1}, 0.01, 0.1, seed), {}, {}};
    c.camera = test::frame_scene(c.particles, {0.2, 0.3, -1}, 160, 120);
    c.options.grid.alpha_degrees = 1;
    c.options.gap_bridging = seed == 1 ? 0 : 0.01;
    check(c, seed == 1 ? "random cloud" : "random cloud, g = 0.01");
  }
}

}  // namespace
}  // namespace voxspan
