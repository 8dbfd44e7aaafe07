// The surface filter ([ZD15] sec. 3.4, 4.6): stable over 100 iterations on the dam break (no
// NaN, no span lost or turned inside out, span order kept, no depth moved by more than the
// radius) while it smooths the surface; a one-particle droplet and thin sheets survive;
// silhouettes do not bleed into what lies behind them; the iteration count follows the depth,
// and its cap the picture's size.
#include <algorithm>
#include <cmath>
#include <random>

#include "render/model/host.h"
#include "render/surface_passes.h"
#include "tests/render/gl/render_fixture.h"
#include "tests/render/gl/shading_fixture.h"
#include "tools/scenes/scenes.h"

namespace voxspan {
namespace {

// Median angle (degrees) between the entry normals of points `step` links apart along the rows
// and the columns: the surface's roughness at that many pixels (the median leaves out the true
// edges of the shape).
double roughness(const SpanImage& spans, const std::vector<glm::uvec2>& links,
                 const std::vector<glm::uvec2>& normals, int step = 1) {
  model::Host host(spans, {});
  std::vector<double> angles;
  for (int y = 0; y < spans.height(); ++y)
    for (int x = 0; x < spans.width(); ++x)
      for (std::uint32_t k = 0; k < spans.pixel(x, y).count; ++k) {
        const std::uint32_t s = spans.pixel(x, y).offset + k;
        const glm::vec3 a = host.decode_normal(normals[s].x);
        for (int dir : {1, 3}) {
          glm::ivec2 q(x, y);
          std::uint32_t t = s;
          for (int i = 0; i < step && t != UINT32_MAX; ++i) {
            const std::uint32_t b = links[t].x >> (8 * dir) & 255;
            q += dir == 1 ? glm::ivec2(1, 0) : glm::ivec2(0, 1);
            t = b > 252 || q.x >= spans.width() || q.y >= spans.height()
                    ? UINT32_MAX
                    : spans.pixel(q.x, q.y).offset + b;
          }
          if (t == UINT32_MAX) continue;
          const glm::vec3 c = host.decode_normal(normals[t].x);
          angles.push_back(test::degrees_between(a, c));
        }
      }
  if (angles.empty()) return 0;
  std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
  return angles[angles.size() / 2];
}

// The max_screen_radius that caps the filter at exactly n iterations on a picture `height` high.
double cap_at(int n, int height) { return std::sqrt((n - 0.5) / 2) / height; }

// One span per pixel of a w x h image, entry and exit each with independent uniform noise of
// +-amplitude: a sheet linked all round.
SpanImage noisy_sheet(int w, int h, float entry, float exit, float amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(-amplitude, amplitude);
  std::vector<std::vector<Span>> columns(std::size_t(w) * std::size_t(h));
  for (auto& c : columns) c.push_back({entry + noise(rng), exit + noise(rng)});
  return test::hand_made(w, h, columns);
}

TEST(Filter, HundredIterationsOnTheDamBreakStayStable) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  test::Particles particles = test::dam_break(shape, 0.3);
  const glm::dvec3 droplet(0.9, 0.45, 0.15);  // one particle, far from the rest
  particles.push_back({float(droplet.x), float(droplet.y), float(droplet.z), 0.02f});
  VoxelizeOptions options;
  options.gap_bridging = shape.spacing;
  const Camera camera = test::frame_scene(particles, {0.4, -0.5, -1}, 192, 108);
  const SpanImage spans = test::voxelize(camera, particles, options);

  SurfaceOptions filter;
  filter.filter_radius = 0.15;  // 2 (r / pixel)^2 > 100 at every depth of the frame
  filter.max_screen_radius = cap_at(100, spans.height());
  ASSERT_GT(filter_iterations_at(spans.grid, filter.filter_radius, spans.grid.grid_far()), 100);
  const ShadeOptions shade = test::test_shading(ShadeMode::translucent);
  const test::GpuResult before = test::shade_on_gpu(spans, {}, shade);
  const test::GpuResult after = test::shade_on_gpu(spans, filter, shade);
  EXPECT_EQ(after.stats.count("filter.iterations"), 100);
  ASSERT_EQ(after.depths.size(), spans.spans.size());

  double most = 0, sum = 0;
  std::size_t closed = 0;
  for (int y = 0; y < spans.height(); ++y)
    for (int x = 0; x < spans.width(); ++x) {
      const PixelSpans& p = spans.pixel(x, y);
      for (std::uint32_t k = 0; k < p.count; ++k) {
        const std::uint32_t s = p.offset + k;
        const glm::vec2 d = after.depths[s];
        ASSERT_TRUE(std::isfinite(d.x) && std::isfinite(d.y)) << x << "," << y;
        ASSERT_LE(d.x, d.y) << "span turned inside out at " << x << "," << y;
        closed += d.x == d.y;
        if (k > 0) {
          ASSERT_GE(d.x, after.depths[s - 1].y) << "spans out of order at " << x << "," << y;
        }
        for (float change : {d.x - spans.spans[s].entry, d.y - spans.spans[s].exit}) {
          most = std::max(most, double(std::abs(change)));
          sum += std::abs(change);
        }
      }
    }
  EXPECT_LE(most, filter.filter_radius * (1 + 1e-6));
  for (float c : after.image.rgba) ASSERT_TRUE(std::isfinite(c));
  // At a working radius (two particle spacings) the filter makes the surface smoother.
  SurfaceOptions working;
  working.filter_radius = 2 * shape.spacing;
  const test::GpuResult smoothed = test::shade_on_gpu(spans, working, shade);
  const double smooth_before = roughness(spans, before.links, before.normals);
  const double smooth_after = roughness(spans, smoothed.links, smoothed.normals);
  std::printf("working radius: %lld iterations, neighbour normals %.2f -> %.2f degrees apart\n",
              static_cast<long long>(smoothed.stats.count("filter.iterations")), smooth_before,
              smooth_after);
  EXPECT_LT(smooth_after, 0.7 * smooth_before) << "the filter should smooth the surface";
  const double hundred = roughness(spans, after.links, after.normals);
  std::printf(
      "100 iterations: largest depth change %.4f (radius %.2f), mean %.5f; neighbour "
      "normals %.2f degrees apart; %zu of %zu spans closed to a sheet\n",
      most, filter.filter_radius, sum / (2.0 * double(spans.spans.size())), hundred, closed,
      spans.spans.size());
  EXPECT_LT(closed, spans.spans.size() / 100);

  // The droplet survives: its pixels keep their span, nearly where it was.
  const glm::dvec3 v = spans.grid.view().to_view(droplet);
  const int px = int((v.x / v.z / spans.grid.view().tan_half_x + 1) * 0.5 * spans.width());
  const int py = int((1 - v.y / v.z / spans.grid.view().tan_half_y) * 0.5 * spans.height());
  const PixelSpans& dp = spans.pixel(px, py);
  ASSERT_GE(dp.count, 1u) << "the droplet should cover pixel " << px << "," << py;
  const glm::vec2 d = after.depths[dp.offset + dp.count - 1];
  EXPECT_LT(d.x, d.y);
  EXPECT_NEAR(d.x, spans.spans[dp.offset + dp.count - 1].entry, 0.02);
}

TEST(Filter, SilhouettesDoNotBleedAndFlatSurfacesStay) {
  // A disc at depth 2 in front of a wall at depth 4, both flat: nothing may move, in
  // particular no depth of the wall next to the disc's silhouette, nor of the disc's rim.
  const int w = 24, h = 24;
  std::vector<std::vector<Span>> columns(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto& c = columns[std::size_t(x) + std::size_t(y) * w];
      if ((x - 12) * (x - 12) + (y - 12) * (y - 12) < 36) c.push_back({2.0f, 2.5f});
      c.push_back({4.0f, 4.5f});
    }
  // The disc and the wall are flat in 1/z only if they face the eye at constant depth: they do.
  const SpanImage spans = test::hand_made(w, h, columns);
  SurfaceOptions filter;
  filter.filter_radius = 1.0;
  filter.max_screen_radius = cap_at(30, h);
  const test::GpuResult r =
      test::shade_on_gpu(spans, filter, test::test_shading(ShadeMode::opaque));
  EXPECT_EQ(r.stats.count("filter.iterations"), 30);
  for (std::size_t s = 0; s < spans.spans.size(); ++s) {
    EXPECT_NEAR(r.depths[s].x, spans.spans[s].entry, 2e-6) << "span " << s;
    EXPECT_NEAR(r.depths[s].y, spans.spans[s].exit, 2e-6) << "span " << s;
  }
}

TEST(Filter, ThinNoisySheetSurvives) {
  // A sheet 0.004 thick (about 3 layers at 14 degrees) whose entry and exit depths carry
  // independent noise of +-0.0015: the filter smooths both sides without letting them cross.
  const SpanImage spans = noisy_sheet(32, 32, 3.0f, 3.004f, 0.0015f, 9);
  SurfaceOptions filter;
  filter.filter_radius = 0.5;
  filter.max_screen_radius = cap_at(50, 32);
  const test::GpuResult r =
      test::shade_on_gpu(spans, filter, test::test_shading(ShadeMode::translucent));
  double spread_before = 0, spread_after = 0;
  for (std::size_t s = 0; s < spans.spans.size(); ++s) {
    ASSERT_LT(r.depths[s].x, r.depths[s].y) << "span " << s;
    spread_before += std::abs(spans.spans[s].entry - 3.0f) + std::abs(spans.spans[s].exit - 3.004f);
    spread_after += std::abs(r.depths[s].x - 3.0f) + std::abs(r.depths[s].y - 3.004f);
  }
  EXPECT_LT(spread_after, 0.3 * spread_before) << "the noise should be smoothed away";
}

TEST(Filter, ASlopingPlaneKeepsItsDepthUpToItsEdges) {
  // A plane sloping across the picture (1/z linear along the rows and the columns) over a
  // disc, nothing around it: a symmetric kernel leaves a plane where it is, up to the disc's
  // silhouette, where a one-sided mean would pull each edge point towards the disc's middle
  // (the one-sided walk moved them by up to 2.8 % of the depth).
  const int w = 48, h = 48;
  std::vector<std::vector<Span>> columns(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if ((x - 24) * (x - 24) + (y - 24) * (y - 24) < 400) {
        const float z = 1.0f / (0.5f + 0.004f * float(x) + 0.002f * float(y));
        columns[std::size_t(x) + std::size_t(y) * w].push_back({z, z + 0.5f});
      }
  const SpanImage spans = test::hand_made(w, h, columns);
  SurfaceOptions filter;
  filter.filter_radius = 10.0;  // far beyond the slope: the bounds do not act
  filter.max_screen_radius = cap_at(32, h);
  const test::GpuResult r =
      test::shade_on_gpu(spans, filter, test::test_shading(ShadeMode::opaque));
  ASSERT_EQ(r.stats.count("filter.iterations"), 32);
  double worst = 0;
  for (std::size_t s = 0; s < spans.spans.size(); ++s)
    worst = std::max(worst, std::abs(double(r.depths[s].x) / spans.spans[s].entry - 1));
  EXPECT_LT(worst, 1e-5) << "largest relative change of the plane's depth";
}

TEST(Filter, EqualsTheIteratedKernelWhereTheSurfaceIsLinkedAllRound) {
  // A surface linked all round (one span per pixel, small noise on the depths): away from the
  // image's edges, where the links end, the filter's passes give what n iterations of the
  // 3x3 binomial kernel on 1/z give, to float rounding.
  const int w = 64, h = 64, n = 8;
  const SpanImage spans = noisy_sheet(w, h, 3.0f, 3.5f, 0.002f, 3);
  SurfaceOptions filter;
  filter.filter_radius = 1.0;  // far beyond the noise: the bounds do not act
  filter.max_screen_radius = cap_at(n, h);
  const test::GpuResult r =
      test::shade_on_gpu(spans, filter, test::test_shading(ShadeMode::opaque));
  ASSERT_EQ(r.stats.count("filter.iterations"), n);
  // The iterated kernel, in double, on the entries' reciprocal depths.
  std::vector<double> inv(std::size_t(w) * h), next(inv.size());
  for (std::size_t i = 0; i < inv.size(); ++i) inv[i] = 1.0 / spans.spans[i].entry;
  for (int it = 0; it < n; ++it) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double sum = 0, weight = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (x + dx < 0 || x + dx >= w || y + dy < 0 || y + dy >= h) continue;
            const double k = (dx == 0 ? 2 : 1) * (dy == 0 ? 2 : 1);
            sum += k * inv[std::size_t(x + dx) + std::size_t(y + dy) * w];
            weight += k;
          }
        next[std::size_t(x) + std::size_t(y) * w] = sum / weight;
      }
    std::swap(inv, next);
  }
  double worst = 0;
  for (int y = n; y < h - n; ++y)
    for (int x = n; x < w - n; ++x) {
      const std::size_t i = std::size_t(x) + std::size_t(y) * w;
      worst = std::max(worst, std::abs(double(r.depths[i].x) - 1.0 / inv[i]));
    }
  EXPECT_LT(worst, 2e-6) << "largest difference from the iterated kernel, away from the edges";
}

TEST(Filter, IterationsFollowTheDepth) {
  const SpanImage spans = test::hand_made(100, 100, std::vector<std::vector<Span>>(10000));
  const double pixel = 2 * spans.grid.view().tan_half_y / spans.height();  // at depth 1
  // 2 (r / pixel(z))^2: constant world radius, so a quarter of the iterations at twice the depth.
  EXPECT_EQ(filter_iterations_at(spans.grid, 3 * pixel, 1.0), 18);
  EXPECT_EQ(filter_iterations_at(spans.grid, 3 * pixel, 2.0), std::ceil(18 / 4.0));
  EXPECT_EQ(filter_iterations_at(spans.grid, 3 * pixel, 3.0), 2);
}

TEST(Filter, ACapOnTheScreenSmoothsEverySizeAlike) {
  // A flat slab of lattice spheres at 192x108 and at four times the size: the same world radius
  // stands for 16 times the iterations in the larger picture, whose bumps are then no rougher
  // in the world (normals the same world distance apart; measured 0.19 and 0.02 degrees). A
  // fixed cap of 32 iterations, the old rule, smoothed the larger picture a third as far and
  // left more than twice the bumps (0.06).
  const double spacing = 0.02;
  const test::Particles particles = test::lattice_block({0, 0, 0}, {40, 40, 3}, spacing, spacing);
  VoxelizeOptions options;
  options.gap_bridging = spacing;
  SurfaceOptions filter;
  filter.filter_radius = spacing;
  const ShadeOptions shade = test::test_shading(ShadeMode::opaque);
  double iterations[3], turn[3];
  for (int k : {0, 1, 2}) {
    const int scale = k == 0 ? 1 : 4;
    const Camera camera = test::frame_scene(particles, {0.4, -0.5, -1}, 192 * scale, 108 * scale);
    const SpanImage spans = test::voxelize(camera, particles, options);
    SurfaceOptions o = filter;
    if (k == 2) o.max_screen_radius = cap_at(32, spans.height());
    const test::GpuResult r = test::shade_on_gpu(spans, o, shade);
    iterations[k] = double(r.stats.count("filter.iterations"));
    turn[k] = roughness(spans, r.links, r.normals, scale);
  }
  std::printf(
      "iterations %.0f, %.0f (capped at 32: %.0f); neighbour normals %.2f, %.2f (%.2f) degrees "
      "apart\n",
      iterations[0], iterations[1], iterations[2], turn[0], turn[1], turn[2]);
  EXPECT_NEAR(iterations[1], 16 * iterations[0], 16);
  EXPECT_LT(turn[1], turn[0]);
  EXPECT_LT(turn[1], 0.6 * turn[2]);
}

}  // namespace
}  // namespace voxspan
