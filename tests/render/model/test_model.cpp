// The shared model files (render/model/*.glsl) as the CPU compiles them: octahedral normals
// (and the GPU's compilation of the same file against the CPU's), Fresnel, Snell's law and
// total internal reflection, the environment, Beer-Lambert over spans (exact past a span cap)
// and a straight path through a flat slab, each against numbers worked out by hand; the walls'
// and the environment's light for refracted rays over their footprints (the backdrop's pyramid).
#include <cmath>
#include <random>

#include "render/backdrop.h"
#include "render/model/host.h"
#include "render/reference/reference_shading.h"
#include "tests/render/gl/shading_fixture.h"

namespace voxspan {
namespace {

using model::Host;

// One environment colour everywhere and no sun: every lookup gives `c`.
ShadeOptions uniform_environment(ShadeMode mode, glm::dvec3 c) {
  ShadeOptions o = test::test_shading(mode);
  Environment& e = o.environment;
  e.sky_zenith = e.sky_horizon = e.ground_light = e.ground_dark = c;
  e.sun_color = {0, 0, 0};
  return o;
}

TEST(Model, OctahedralNormalsRoundTrip) {
  const SpanImage none = test::hand_made(1, 1, {{}});
  Host host(none, {});
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  std::vector<glm::vec4> inputs;
  for (int i = 0; i < 20000; ++i)
    inputs.emplace_back(glm::normalize(glm::vec3(g(rng), g(rng), g(rng))), 0.0f);
  for (glm::vec3 axis :
       {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)})
    inputs.emplace_back(axis, 0.0f);
  double worst = 0;
  for (const glm::vec4& v : inputs)
    worst = std::max(
        worst,
        test::degrees_between(host.decode_normal(host.encode_normal(glm::vec3(v))), glm::vec3(v)));
  EXPECT_LT(worst, 0.01) << "degrees";

  // The GPU's compilation of the same file gives the same words, and decodes them alike.
  const auto n = static_cast<unsigned>(inputs.size());
  gl::Program probe = test::shaders().compute("tests/render/model/octahedral_probe.comp");
  gl::Buffer in(inputs.size() * 16, inputs.data()), words(inputs.size() * 4),
      decoded(inputs.size() * 16);
  in.bind(GL_SHADER_STORAGE_BUFFER, 0);
  words.bind(GL_SHADER_STORAGE_BUFFER, 1);
  decoded.bind(GL_SHADER_STORAGE_BUFFER, 2);
  probe.set("u_count", n);
  probe.dispatch((n + 63) / 64);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const auto gpu_words = words.read<std::uint32_t>(n);
  const auto gpu_decoded = decoded.read<glm::vec4>(n);
  int differing = 0;
  for (unsigned i = 0; i < n; ++i) {
    const std::uint32_t cpu = host.encode_normal(glm::vec3(inputs[i]));
    const glm::ivec2 a(std::int16_t(cpu & 0xFFFF), std::int16_t(cpu >> 16));
    const glm::ivec2 b(std::int16_t(gpu_words[i] & 0xFFFF), std::int16_t(gpu_words[i] >> 16));
    differing += a != b;
    ASSERT_LE(std::abs(a.x - b.x) + std::abs(a.y - b.y), 2) << "input " << i;
    ASSERT_LT(test::degrees_between(glm::vec3(gpu_decoded[i]), host.decode_normal(gpu_words[i])),
              1e-3);
  }
  EXPECT_LT(differing, int(n) / 100) << "words differing by a rounding step";
}

// A 16 x 8 backdrop of one-pixel stripes, red and blue by column, whose right half stands no
// wall (kNoWall pixels, coloured to show if they leaked in): rays ending on it at `spread`
// pixels from their neighbours' ends see the mean of the walls over that footprint.
glm::vec3 wall_light_with_spread(float spread, glm::vec2 land) {
  Backdrop b;
  b.width = 16;
  b.height = 8;
  b.version = 1;
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x)
      b.pixels.push_back(x >= 8       ? glm::vec4(100, 100, 100, Backdrop::kNoWall)
                         : x % 2 == 0 ? glm::vec4(1, 0, 0, 2)
                                      : glm::vec4(0, 0, 1, 2));
  std::vector<glm::vec4> pyramid;
  backdrop_pyramid(b, pyramid);
  const SpanImage none = test::hand_made(b.width, b.height, std::vector<std::vector<Span>>(128));
  Host host(none, {});
  host.use_backdrop(&pyramid);
  // Every ray ends on the walls at its pixel's centre scaled by `spread` about pixel (4, 4).
  host.ends_.resize(b.pixels.size());
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x)
      host.ends_[host.pixel_index({x, y})].end =
          glm::vec4(land + spread * glm::vec2(float(x - 4), float(y - 4)), 0, VX_END_WALLS);
  return host.wall_light({4, 4}, land);
}

TEST(Model, RefractedRaysSeeTheWallsOverTheirFootprint) {
  // Level 0 and each level above it: ceil halves of the one below, kBackdropLevels of them.
  Backdrop b;
  b.width = 5;
  b.height = 3;
  b.pixels.assign(15, glm::vec4(0.5f, 0.25f, 1.0f, 2.0f));
  b.pixels[0].a = Backdrop::kNoWall;
  std::vector<glm::vec4> pyramid;
  backdrop_pyramid(b, pyramid);
  std::size_t texels = 0;
  for (int level = 0, w = 5, h = 3; level < kBackdropLevels;
       ++level, w = (w + 1) / 2, h = (h + 1) / 2)
    texels += std::size_t(w) * std::size_t(h);
  ASSERT_EQ(pyramid.size(), texels);
  EXPECT_EQ(pyramid[15], glm::vec4(0.375f, 0.1875f, 0.75f, 0.75f)) << "3 walls of 4, premultiplied";
  EXPECT_EQ(pyramid[16], glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));

  // Neighbours ending one pixel apart: the pixel's own colour, at its centre or between two.
  EXPECT_EQ(wall_light_with_spread(1, {4.5f, 4.5f}), glm::vec3(1, 0, 0));
  EXPECT_EQ(wall_light_with_spread(1, {5.5f, 4.5f}), glm::vec3(0, 0, 1));
  const glm::vec3 between = wall_light_with_spread(1, {5.0f, 4.5f});
  EXPECT_NEAR(between.r, 0.5f, 1e-6);
  EXPECT_NEAR(between.b, 0.5f, 1e-6);
  // Spread over 4 and 8 pixels: the stripes' mean, and never the pixels with no wall.
  for (float spread : {4.0f, 8.0f}) {
    const glm::vec3 c = wall_light_with_spread(spread, {4.5f, 4.5f});
    EXPECT_NEAR(c.r, 0.5f, 0.02f) << spread;
    EXPECT_NEAR(c.b, 0.5f, 0.02f) << spread;
    EXPECT_LE(c.r + c.g + c.b, 1.0f + 1e-5f) << spread;
  }
}

// A ray of pixel (1, 1) of 3 x 3 leaving from 1 above the middle of a light checker tile straight
// down, its neighbours' rays `spread` radians beside it (half the angle between them): the
// environment it sees (environment_light), `bent` by the fluid or not.
glm::vec3 environment_light_with_spread(float spread, bool bent) {
  const SpanImage none = test::hand_made(3, 3, std::vector<std::vector<Span>>(9));
  ShadeOptions o = test::test_shading(ShadeMode::refractive);
  o.environment.ground_height = 0;
  o.environment.ground_tile = 0.1;
  o.environment.sun_color = {0, 0, 0};
  Host host(none, model::shade_uniforms(o));
  const glm::vec3 up = host.u_env_up;
  const glm::vec3 across = host.u_env_axis_a;
  // (0.05, 0.05) along the ground's axes: the middle of the tile at the origin.
  const glm::vec3 start = 0.05f * (host.u_env_axis_a + host.u_env_axis_b) + up;
  const glm::vec3 anchor = host.world_to_view_direction(start - host.u_eye);
  host.ends_.assign(9, {});
  for (int k = 0; k < 9; ++k) {
    const glm::vec3 world =
        k == 4 ? -up : std::cos(2 * spread) * -up + std::sin(2 * spread) * across;
    host.ends_[std::size_t(k)] = {glm::vec4(host.world_to_view_direction(world), VX_END_LEFT),
                                  glm::vec3(1), anchor, bent};
  }
  return host.environment_light({1, 1}, anchor, glm::vec3(host.ends_[4].end), bent);
}

TEST(Model, RefractedRaysSeeTheEnvironmentOverTheirFootprint) {
  // Neighbours close by: the tile's own colour, as a point sample; far apart (a footprint 2 x 0.2
  // wide from 1 above the ground: four tiles): the mean of the light and dark tiles.
  const glm::vec3 point = environment_light_with_spread(1e-4f, true);
  const glm::vec3 wide = environment_light_with_spread(0.2f, true);
  ShadeOptions o = test::test_shading(ShadeMode::refractive);
  const float light = float(o.environment.ground_light.r);
  const float dark = float(o.environment.ground_dark.r);
  EXPECT_NEAR(point.r, environment_light_with_spread(0, true).r, 1e-6);
  EXPECT_GT(std::abs(point.r - wide.r), 0.25f * (light - dark)) << point.r << " " << wide.r;
  EXPECT_GT(wide.r, dark + 0.25f * (light - dark));
  EXPECT_LT(wide.r, light - 0.25f * (light - dark));
  // A ray the fluid did not bend sees the point the other modes' background sees.
  EXPECT_EQ(environment_light_with_spread(0.2f, false), environment_light_with_spread(0, false));
}

TEST(Model, FresnelAndSnell) {
  const SpanImage none = test::hand_made(1, 1, {{}});
  Host host(none, model::shade_uniforms(test::test_shading(ShadeMode::refractive)));
  const float ior = host.u_ior;
  const float f0 = std::pow((ior - 1) / (ior + 1), 2.0f);
  EXPECT_NEAR(host.fresnel(1.0f), f0, 1e-7);
  EXPECT_NEAR(host.fresnel(0.0f), 1.0f, 1e-7);
  EXPECT_LT(host.fresnel(0.9f), host.fresnel(0.5f));

  const glm::vec3 n(0, 0, -1);  // outward normal of a surface facing the eye
  for (float degrees : {0.0f, 20.0f, 45.0f, 70.0f}) {
    const float a = glm::radians(degrees);
    Host::RayState s = host.ray_start({0, 0});
    s.bounces = host.u_bounces;  // past the pixel's front surface (which has no span here)
    s.dir = glm::vec3(std::sin(a), 0.0f, std::cos(a));
    s.throughput = glm::vec3(1.0f);
    s.color = glm::vec3(0.0f);
    const Host::RayState in = host.ray_interface(s, n, true);
    EXPECT_TRUE(in.inside);
    const float sin_t = std::sqrt(in.dir.x * in.dir.x + in.dir.y * in.dir.y);
    EXPECT_NEAR(sin_t * ior, std::sin(a), 1e-5) << degrees << " degrees in";
    EXPECT_NEAR(in.throughput.x, 1 - host.fresnel(std::cos(a)), 1e-6);
    EXPECT_GT(in.color.x + in.color.y + in.color.z, 0.0f) << "reflection of the environment";
  }
  // Leaving through the back (outward normal away from the eye): Snell below the critical
  // angle; just below it the reflected share (Fresnel > 1/2) dominates and the ray follows
  // it; total internal reflection above it.
  const glm::vec3 back(0, 0, 1);
  const float critical = std::asin(1 / ior);
  for (float a : {critical - 0.05f, critical - 0.003f, critical + 0.05f}) {
    Host::RayState s = host.ray_start({0, 0});
    s.inside = true;
    s.dir = glm::vec3(std::sin(a), 0.0f, std::cos(a));
    const Host::RayState out = host.ray_interface(s, back, false);
    if (a < critical - 0.01f) {
      EXPECT_FALSE(out.inside);
      EXPECT_NEAR(std::sqrt(out.dir.x * out.dir.x + out.dir.y * out.dir.y), ior * std::sin(a),
                  1e-4);
      EXPECT_LT(out.throughput.x, 1.0f);
    } else {
      EXPECT_TRUE(out.inside) << "internal reflection keeps the ray inside";
      EXPECT_NEAR(out.dir.x, std::sin(a), 1e-5);
      EXPECT_NEAR(out.dir.z, -std::cos(a), 1e-5);
      if (a > critical) {
        EXPECT_EQ(out.throughput, s.throughput) << "total: nothing leaves";
      } else {
        EXPECT_GT(out.throughput.x, 0.5f);
        EXPECT_LT(out.throughput.x, 1.0f);
      }
    }
  }
}

TEST(Model, EnvironmentSkyGroundAndHorizon) {
  const SpanImage none = test::hand_made(1, 1, {{}});
  ShadeOptions o = test::test_shading(ShadeMode::opaque);
  o.environment.sun_color = {0, 0, 0};
  Host host(none, model::shade_uniforms(o));
  const glm::vec3 eye(0, 1, 0);
  EXPECT_NEAR(glm::distance(host.environment(eye, {0, 1, 0}), glm::vec3(o.environment.sky_zenith)),
              0, 1e-6);
  // Straight down onto the ground: a checker tile's colour (light or dark, or between at an edge).
  const glm::vec3 ground = host.environment(eye, {0, -1, 0});
  EXPECT_LE(ground.r, float(o.environment.ground_light.r) + 1e-6f);
  EXPECT_GE(ground.r, float(o.environment.ground_dark.r) * 0.9f);
  // The pattern changes from tile to tile.
  const glm::vec3 a = host.environment({0.05, 1, 0.05}, {0, -1, 0});
  const glm::vec3 b = host.environment({0.15, 1, 0.05}, {0, -1, 0});
  EXPECT_GT(glm::distance(a, b), 0.2f);
  // Far towards the horizon the ground fades into the sky's horizon colour: no seam.
  const glm::vec3 above = host.environment(eye, glm::normalize(glm::vec3(1, 1e-4f, 0)));
  const glm::vec3 below = host.environment(eye, glm::normalize(glm::vec3(1, -1e-4f, 0)));
  EXPECT_LT(glm::distance(above, below), 0.01f);

  // A footprint across the horizon takes the sky and the ground by the share of its elevations
  // above and below it: looking level from 1 above the ground over a cone 0.6 wide, half each.
  const glm::vec3 level(1, 0, 0);
  const glm::vec3 sky = host.sky_color(host.at_elevation(level, 0.3f));
  const glm::vec3 ground_below = host.ground_over(eye, host.at_elevation(level, -0.3f), 0.6f);
  const glm::vec3 cone = host.environment_over(eye, level, 0.6f);
  EXPECT_LT(glm::distance(cone, 0.5f * (sky + ground_below)), 1e-5f);
  EXPECT_EQ(host.environment_over(eye, level, 0.0f), host.sky_color(level)) << "a point: the sky";
  // Continuous where the cone's edge reaches the horizon, from either side.
  for (float e : {0.6f, -0.6f}) {
    const glm::vec3 edge = host.at_elevation(level, e);
    const glm::vec3 in = host.environment_over(eye, host.at_elevation(level, e * 0.999f), 0.6f);
    EXPECT_LT(glm::distance(host.environment_over(eye, edge, 0.6f), in), 0.01f) << e;
  }
}

TEST(Model, TranslucentBeerLambertExactPastTheCap) {
  // One pixel looking down the axis through 24 slabs of 0.05 with gaps of 0.05, uncapped and
  // capped at 7 (the 7th span extended to the last exit, `inside` still counting fluid only).
  std::vector<Span> all, capped;
  for (int k = 0; k < 24; ++k) all.push_back({2.0f + 0.1f * k, 2.05f + 0.1f * k});
  capped.assign(all.begin(), all.begin() + 7);
  capped.back().exit = all.back().exit;
  SpanImage a = test::hand_made(1, 1, {all});
  SpanImage c = test::hand_made(1, 1, {capped});
  c.pixels[0].total = 24;
  c.pixels[0].inside = a.pixels[0].inside;
  const glm::dvec3 env(0.6, 0.7, 0.8);
  const ShadeOptions o = uniform_environment(ShadeMode::translucent, env);
  const glm::vec4 got_all = reference_shading(a, o).at(0, 0);
  const glm::vec4 got_capped = reference_shading(c, o).at(0, 0);
  // By hand: F at normal incidence, T = exp(-absorption * 24 * 0.05), scattering (1 - T) * s.
  const double f = std::pow((o.material.ior - 1) / (o.material.ior + 1), 2);
  for (int ch = 0; ch < 3; ++ch) {
    const double t = std::exp(-o.material.absorption[ch] * 24 * 0.05);
    const double want =
        f * env[ch] + (1 - f) * (t * env[ch] + (1 - t) * o.material.scatter_color[ch]);
    EXPECT_NEAR(got_all[ch], want, 2e-5) << "channel " << ch;
    EXPECT_NEAR(got_capped[ch], want, 2e-5) << "channel " << ch << ", capped";
  }
}

TEST(Model, RefractionStraightThroughAFlatSlab) {
  // A slab [2, 3] in depth over a 9 x 9 image: the centre ray meets it head on, goes straight
  // through and leaves: F at entry, (1 - F) twice, Beer-Lambert over 1, scattering on the way.
  std::vector<std::vector<Span>> columns(81, std::vector<Span>{{2.0f, 3.0f}});
  const SpanImage slab = test::hand_made(9, 9, columns);
  const glm::dvec3 env(0.6, 0.7, 0.8);
  const ShadeOptions o = uniform_environment(ShadeMode::refractive, env);
  const glm::vec4 got = reference_shading(slab, o).at(4, 4);
  const double f = std::pow((o.material.ior - 1) / (o.material.ior + 1), 2);
  const double len = 1.0 * slab.grid.view().ray_scale(4, 4);
  for (int ch = 0; ch < 3; ++ch) {
    const double t = std::exp(-o.material.absorption[ch] * len);
    const double want =
        f * env[ch] + (1 - f) * ((1 - t) * o.material.scatter_color[ch] + t * (1 - f) * env[ch]);
    EXPECT_NEAR(got[ch], want, 1e-4) << "channel " << ch;
  }
  // And the GPU agrees.
  const glm::vec4 gpu = test::shade_on_gpu(slab, {}, o).image.at(4, 4);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(gpu[ch], got[ch], 1e-5);
}

}  // namespace
}  // namespace voxspan
