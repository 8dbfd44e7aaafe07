// The stability suite's scenes, each through both renderers (stability_fixture.h: finite
// pixels in all three shading modes, bounded spans and GPU memory, the GL spans within the
// voxelization's bounds of the exact reference and the CPU ones equal to it), with what each
// case adds: hard depth complexity (more layers than the span cap, a 3D checkerboard), geometry
// below the grid's resolution (sheets thinner than a layer, droplets of a pixel or less, radii
// over three orders of magnitude), degenerate particle sets (every particle in one cell, on
// one point) and awkward cameras (inside the fluid, grazing its surface, the near plane
// cutting through spheres).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stability_fixture.h"
#include "tools/scenes/scene_cell_states.h"
#include "voxspan/classify.h"

namespace voxspan {
namespace {

test::Scene scene_of(std::string name, test::Particles particles, glm::dvec3 direction,
                     int width = 96, int height = 64) {
  test::Scene s;
  s.name = std::move(name);
  s.particles = std::move(particles);
  s.camera = test::frame_scene(s.particles, direction, width, height);
  return s;
}

// 24 sheets along the view, a cap of 7: the central rays find 24 spans and store 7, the last
// extended to the last exit with the gaps left out of `inside` (sec. 3.1), so memory stays at
// pixels x 7 spans however deep the fluid is.
TEST(Stability, MoreLayersThanTheSpanCap) {
  test::Scene s;
  s.name = "24 layers, cap 7";
  s.particles = test::stacked_layers(24, 16, 1, 0.075, 0.07, 0.2);
  s.camera = test::look_at({0.6, 0.56, -1.0}, {0.56, 0.56, 1.0}, 96, 64);
  s.voxelize.max_spans = 7;
  s.voxelize.grid.alpha_degrees = 2;
  s.surfaces.filter_radius = 0.07;
  const test::Checked c = test::check_both(s);
  for (const test::Frame* f : {&c.gl, &c.cpu}) {
    const PixelSpans& centre = f->spans.pixel(48, 32);
    EXPECT_EQ(centre.count, 7u);
    EXPECT_EQ(centre.total, 24u);
    EXPECT_GT(f->stats.count("pixels.capped"), 96 * 64 / 4);
    EXPECT_EQ(f->stats.count("pixels.capped"), f->spans.capped_pixels());
  }
}

// Alternate blocks filled, seen along a diagonal: many short spans and gaps per ray, surfaces
// that change from pixel to pixel; the links and the filter must stay finite on them.
TEST(Stability, CheckerboardIn3D) {
  test::Scene s =
      scene_of("3D checkerboard", test::checkerboard(4, 3, 0.06, 0.055), {0.6, -0.5, -1});
  s.voxelize.max_spans = 3;
  s.voxelize.gap_bridging = 0.03;
  s.voxelize.grid.alpha_degrees = 3;
  s.surfaces.filter_radius = 0.06;
  const test::Checked c = test::check_both(s);
  EXPECT_GT(c.cpu.spans.capped_pixels(), 0);
}

// A single sheet of spheres whose diameter is a third of the layer thickness at its depth
// (alpha = 30 degrees: a layer is 0.58 pixel), face on and tilted 60 degrees: every pixel the
// sheet covers must get a span (no holes from the voxel grid missing it), one voxel thick or
// more, within one layer of the exact entry and exit.
TEST(Stability, SheetsThinnerThanAVoxel) {
  for (double tilt : {0.0, 60.0}) {
    const Camera camera = test::look_at({0, 0, 5}, {0, 0, 0}, 96, 64);
    test::Scene s;
    s.camera = camera;
    s.voxelize.grid.alpha_degrees = 30;
    const double layer = 5 * std::tan(30 * M_PI / 180) * 2 * std::tan(22.5 * M_PI / 180) / 64;
    const double r = layer / 6;
    const double t = tilt * M_PI / 180;
    for (double u = -0.6; u <= 0.6; u += r)
      for (double v = -0.4; v <= 0.4; v += r)
        s.particles.push_back({float(u * std::cos(t)), float(v), float(u * std::sin(t)), float(r)});
    s.name = tilt == 0 ? "thin sheet, face on" : "thin sheet, tilted 60 deg";
    s.surfaces.filter_radius = 2 * r;
    const test::Checked c = test::check_both(s);
    // Thinner than a layer indeed, and seen over many pixels.
    EXPECT_LT(2 * r, c.cpu.spans.grid.layer_thickness(5.0) / 2);
    EXPECT_GT(c.gl_vs_reference.pixels_hit, 100);
    EXPECT_GE(c.gl.spans.total_spans(), c.reference.total_spans() * 995 / 1000);
  }
}

// Droplets far apart, from a third of a pixel to three pixels across, with gap bridging
// (thin ones are splatted as their entry and exit only): each must show where the exact one
// does, alone in its pixels, neither lost nor smeared.
TEST(Stability, IsolatedDroplets) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> at(-2.0, 2.0), radius(0.01, 0.1);
  test::Particles p;
  for (int i = 0; i < 60; ++i)
    p.push_back({float(at(rng)), float(at(rng) * 0.7), float(at(rng)), float(radius(rng))});
  test::Scene s = scene_of("isolated droplets", p, {0.1, -0.2, -1});
  s.voxelize.gap_bridging = 0.05;
  s.voxelize.grid.alpha_degrees = 4;
  s.surfaces.filter_radius = 0.05;
  const test::Checked c = test::check_both(s);
  EXPECT_GT(c.gl_vs_reference.pixels_hit, 30);
}

// Radii from 0.001 to 1 (log-uniform) in one cloud: the grid's layers are set by the depth
// range, the splat meets spheres far below a pixel and far above a tile; no radius may make a
// pass lose or invent spans.
TEST(Stability, RadiiOverThreeOrdersOfMagnitude) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> at(-1.5, 1.5), log_r(-3.0, 0.0);
  test::Particles p;
  for (int i = 0; i < 400; ++i)
    p.push_back(
        {float(at(rng)), float(at(rng)), float(at(rng)), float(std::pow(10.0, log_r(rng)))});
  p.push_back({0.2f, -0.1f, 0.3f, 0.001f});
  p.push_back({-0.5f, 0.4f, -0.2f, 1.0f});
  test::Scene s = scene_of("radii 0.001 to 1", p, {0.3, 0.2, -1});
  s.voxelize.grid.alpha_degrees = 4;
  s.surfaces.filter_radius = 0.01;
  test::check_both(s);
}

// Every particle in one classifier cell (jittered within it) and every particle on one point:
// one cell full, its neighbours empty, so all of them are boundary particles; the binning puts
// them all in the same tiles. The picture is that of their union, like any other.
TEST(Stability, EveryParticleInOneCell) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> in_cell(0.001, 0.099);
  test::Particles jittered;
  for (int i = 0; i < 3000; ++i)
    jittered.push_back({float(in_cell(rng)), float(in_cell(rng)), float(in_cell(rng)), 0.05f});
  const test::TestCells cells = test::classify_for_test(jittered, 0.1, 8);
  EXPECT_EQ(cells.boundary.size(), jittered.size());
  EXPECT_EQ(cells.inner_full_cells, 0);

  // The classifier itself, through the adapter's API: one full cell.
  std::vector<float> x, y, z;
  for (const ParticleSphere& q : jittered) x.push_back(q.x), y.push_back(q.y), z.push_back(q.z);
  ClassifyOptions options;
  options.particle_spacing = 0.05;
  options.cell_size = 0.1;
  const Classification k = classify(ParticleView::soa(x.data(), y.data(), z.data(), x.size()),
                                    GridView::none(), options);
  EXPECT_EQ(k.counts.cells_full + k.counts.cells_partial, 1u);
  EXPECT_EQ(k.counts.boundary, jittered.size());

  test::Scene s = scene_of("3000 particles in one cell", cells.boundary, {0.3, -0.4, -1});
  s.cells = cells.view;
  s.voxelize.grid.alpha_degrees = 2;
  s.surfaces.filter_radius = 0.05;
  test::check_both(s);

  const test::Particles one_point(2000, ParticleSphere{0.3f, -0.2f, 0.1f, 0.25f});
  test::Scene point = scene_of("2000 particles on one point", one_point, {0, 0, -1});
  point.voxelize.grid.alpha_degrees = 2;
  const test::Checked c = test::check_both(point);
  // The union of one sphere: one span per pixel it covers.
  for (const PixelSpans& q : c.gl.spans.pixels) EXPECT_LE(q.total, 1u);
}

// The eye in the middle of a lattice block whose inside is inner-full cells: every ray starts
// in the fluid, at the near plane (the grid's floor, a fraction of the far depth), and the
// cells around the eye count as fluid from there on.
TEST(Stability, CameraInsideTheFluid) {
  const test::Particles block = test::lattice_block({0, 0, 0}, {16, 16, 16}, 0.05, 0.05);
  const test::TestCells cells = test::classify_for_test(block, 0.1, 8);
  ASSERT_GT(cells.inner_full_cells, 0);
  test::Scene s;
  s.name = "camera inside the fluid";
  s.particles = cells.boundary;
  s.cells = cells.view;
  s.camera = test::look_at({0.41, 0.38, 0.43}, {1.0, 0.5, 0.9}, 96, 64);
  s.voxelize.gap_bridging = 0.05;
  s.voxelize.grid.alpha_degrees = 3;
  s.surfaces.filter_radius = 0.05;
  const test::Checked c = test::check_both(s);
  for (const test::Frame* f : {&c.gl, &c.cpu}) {
    int from_near = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 96; ++x) {
        const auto spans = f->spans.spans_at(x, y);
        from_near += !spans.empty() && spans[0].entry == float(f->spans.grid.near());
      }
    EXPECT_EQ(from_near, 96 * 64);
  }
}

// The eye a hundredth of a radius above the bumpy top of a slab, looking along it: rays meet
// the spheres' caps at grazing angles, with long, thin spans and gaps between bumps. Gap
// bridging of half the spacing, as a solver sets it: without it the gaps between bumps are
// thinner than a layer, which no voxel grid resolves (count match 97.7 %). Then the usual
// bounds hold.
TEST(Stability, CameraGrazingTheSurface) {
  const double r = 0.05;
  const test::Particles slab = test::lattice_block({0, 0, 0}, {40, 4, 20}, 0.05, r);
  const double top = 3.5 * 0.05 + r;  // the highest sphere's top
  test::Scene s;
  s.name = "camera grazing the surface";
  s.particles = slab;
  s.camera = test::look_at({-0.1, top + 0.01 * r, 0.5}, {2.0, top + 0.01 * r, 0.5}, 96, 64);
  s.voxelize.gap_bridging = 0.025;
  s.voxelize.grid.alpha_degrees = 2;
  s.surfaces.filter_radius = r;
  s.ground_height = 0;
  const test::Checked c = test::check_both(s);
  // Below the horizon the rays meet the slab; above it they see the sky.
  EXPECT_GT(c.reference.pixel(48, 40).count, 0u);
  EXPECT_EQ(c.reference.pixel(48, 20).count, 0u);
}

// A near plane set at 1 (GridOptions::min_near) cutting a block that reaches from behind the
// eye to depth 2: spheres across the near plane are clipped to it (their spans start there),
// spheres wholly before it, those behind the eye among them, are culled and counted.
TEST(Stability, ParticlesAcrossTheNearPlane) {
  test::Particles p = test::lattice_block({-0.6, -0.4, -2.0}, {12, 8, 30}, 0.1, 0.08);
  test::Scene s;
  s.name = "particles across the near plane";
  s.camera = test::look_at({0, 0, 0}, {0, 0, -1}, 96, 64);
  s.voxelize.grid.min_near = 1.0;
  s.voxelize.gap_bridging = 0.05;
  s.voxelize.grid.alpha_degrees = 3;
  s.surfaces.filter_radius = 0.08;
  // Culled as behind: wholly before the near plane (depth -z), those behind the eye included.
  std::int64_t behind = 0, behind_eye = 0;
  for (const ParticleSphere& q : p) {
    behind += -q.z + q.radius < 1.0;
    behind_eye += q.z - q.radius > 0;
  }
  ASSERT_GT(behind_eye, 0);
  s.particles = std::move(p);
  const test::Checked c = test::check_both(s);
  for (const test::Frame* f : {&c.gl, &c.cpu}) {
    EXPECT_EQ(f->spans.grid.near(), 1.0);
    EXPECT_EQ(f->stats.count("particles.culled_behind"), behind);
    EXPECT_EQ(f->spans.spans_at(48, 32)[0].entry, 1.0f);
  }
}

}  // namespace
}  // namespace voxspan
