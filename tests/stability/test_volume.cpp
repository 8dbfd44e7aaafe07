// The stability suite's volume cases (render/volume.h), on the CPU renderer and through the merge
// that MPI jobs and deep images use (render_with_deep), each frame's pixels finite:
//   - bad particles (NaN or infinite position or value, h or weight at or below 0, or NaN) are
//     skipped and counted, the picture exactly the clean one's;
//   - no particle, or none in view: the background alone;
//   - the same picture at every scale from 1e-10 to 1e20 world units;
//   - every particle on one point; the camera inside the fluid;
//   - a particle whose support spans more samples than the march holds is refused, naming why.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "render/cpu/volume_caster.h"
#include "render/cpu/volume_renderer.h"
#include "render/volume_merge.h"
#include "tests/support/volume_cloud.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

void expect_finite(const VolumeFrame& f) {
  for (float v : f.picture.rgba) ASSERT_TRUE(std::isfinite(v));
  for (float d : f.depth) ASSERT_TRUE(std::isfinite(d));
}

// The frame by the caster and through the merge (as one rank's part, with its deep image).
struct BothFrames {
  VolumeFrame caster, merged;
  VolumeCounts counts;
};
BothFrames both(const Camera& camera, const std::vector<VolumeParticle>& particles,
                const VolumeOptions& o) {
  BothFrames b;
  VolumeCaster caster;
  b.counts = caster.run(camera, particles, o, b.caster);
  const std::unique_ptr<VolumeRenderer> renderer = make_cpu_volume_renderer();
  Recorder recorder;
  render_with_deep(*renderer, camera, particles, o, recorder, b.merged);
  expect_finite(b.caster);
  expect_finite(b.merged);
  return b;
}

TEST(StabilityVolume, BadParticlesAreSkippedAndCountedThePictureTheCleanOne) {
  const test::Cloud c = test::cloud(6, 5);
  const VolumeOptions o = test::cloud_options(VolumeMode::mixed, c.spacing);
  std::vector<VolumeParticle> dirty = c.particles;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const VolumeParticle& bad : std::vector<VolumeParticle>{{nan, 0, 0, 0.1f, 0.5f, 1},
                                                               {0, inf, 0, 0.1f, 0.5f, 1},
                                                               {0, 0, 0, 0.1f, 0.5f, inf},
                                                               {0, 0, 0, 0.1f, 0.5f, nan},
                                                               {0, 0, 0, 0.0f, 0.5f, 1},
                                                               {0, 0, 0, -0.1f, 0.5f, 1},
                                                               {0, 0, 0, nan, 0.5f, 1},
                                                               {0, 0, 0, 0.1f, 0.0f, 1},
                                                               {0, 0, 0, 0.1f, -1.0f, 1},
                                                               {0, 0, 0, 0.1f, inf, 1}})
    dirty.insert(dirty.begin() + std::ptrdiff_t(dirty.size() / 2), bad);
  const BothFrames clean = both(c.camera, c.particles, o);
  const BothFrames with = both(c.camera, dirty, o);
  EXPECT_EQ(with.counts.particles_invalid, 10);
  EXPECT_EQ(with.caster.picture.rgba, clean.caster.picture.rgba);
  EXPECT_EQ(with.merged.picture.rgba, clean.merged.picture.rgba);
}

TEST(StabilityVolume, NoParticleOrNoneInViewGivesTheBackground) {
  const test::Cloud c = test::cloud(5, 6);
  const VolumeOptions o = test::cloud_options(VolumeMode::mixed, c.spacing);
  std::vector<VolumeParticle> behind = c.particles;
  for (VolumeParticle& p : behind) p.z += 100;  // all behind the eye (it looks down -z)
  const BothFrames none = both(c.camera, {}, o);
  const BothFrames culled = both(c.camera, behind, o);
  EXPECT_EQ(none.counts.samples, 0);
  EXPECT_EQ(culled.counts.samples, 0);
  EXPECT_EQ(culled.counts.particles_culled, std::int64_t(behind.size()));
  EXPECT_EQ(culled.caster.picture.rgba, none.caster.picture.rgba);
  EXPECT_EQ(none.merged.picture.rgba, none.caster.picture.rgba);
}

// Everything scaled by s: positions, h, the camera, the anchor and the opacity length, the
// ground's tile. The particles' weights are dimensionless, so only rounding may differ.
TEST(StabilityVolume, ThePictureIsTheSameAtEveryScale) {
  const test::Cloud c = test::cloud(7, 8);
  const auto at = [&](double s, BothFrames& out) {
    std::vector<VolumeParticle> p = c.particles;
    for (VolumeParticle& q : p) {
      q.x = float(q.x * s), q.y = float(q.y * s), q.z = float(q.z * s), q.h = float(q.h * s);
    }
    Camera camera = c.camera;
    camera.eye *= s;
    camera.target *= s;
    VolumeOptions o = test::cloud_options(VolumeMode::mixed, c.spacing * s);
    o.environment.rest_on_floor(-0.2 * s, c.spacing * s);
    o.environment.ground_tile = 0.5 * s;
    out = both(camera, p, o);
  };
  BothFrames unit;
  at(1, unit);
  for (double scale : {1e-10, 1e-5, 1e5, 1e10, 1e20}) {
    SCOPED_TRACE(scale);
    BothFrames scaled;
    at(scale, scaled);
    double d = 0;
    for (std::size_t i = 0; i < unit.caster.picture.rgba.size(); ++i)
      d = std::max(d,
                   double(std::abs(scaled.caster.picture.rgba[i] - unit.caster.picture.rgba[i])));
    std::printf("scale %g: largest channel difference from unit scale %.2e\n", scale, d);
    EXPECT_LT(d, 1e-4);
    EXPECT_EQ(scaled.counts.samples, unit.counts.samples);
  }
}

TEST(StabilityVolume, EveryParticleOnOnePoint) {
  const test::Cloud c = test::cloud(4, 9);
  VolumeParticle one = c.particles[30];
  one.value = 1;
  std::vector<VolumeParticle> point(2000, one);
  VolumeOptions o = test::cloud_options(VolumeMode::iso, c.spacing);
  o.shepard = false;
  // Each adds weight h^3 W(0) = 0.455 / pi at the centre: 290 for all, 100 a sphere around it.
  o.isos = {{100, {0.9, 0.9, 0.9}, 1}};
  const BothFrames f = both(c.camera, point, o);
  EXPECT_GT(f.counts.iso_hits, 20);
  EXPECT_LT(std::abs(f.merged.picture.rgba[0] - f.caster.picture.rgba[0]), 1e-5);
}

TEST(StabilityVolume, CameraInsideTheFluid) {
  const test::Cloud c = test::cloud(10, 10);
  const VolumeOptions o = test::cloud_options(VolumeMode::dvr, c.spacing);
  const double mid = 0.45;
  const Camera inside = test::look_at({mid, mid, mid}, {mid, mid, 0}, 48, 32, 60);
  const BothFrames f = both(inside, c.particles, o);
  EXPECT_GT(f.counts.samples, 48 * 32 * 3);  // every ray starts in the fluid
  for (std::size_t i = 0; i < f.caster.picture.rgba.size(); ++i)
    EXPECT_NEAR(f.merged.picture.rgba[i], f.caster.picture.rgba[i], 1e-5);
}

TEST(StabilityVolume, ASupportTooLongForTheMarchIsRefusedNamingWhy) {
  // A fine lattice (2000 rows, sampling 16: a sample every 2e-5 of the depth) and a particle
  // around the eye whose support reaches 10^5 times the near plane's depth: 5e5 samples.
  const test::Cloud c = test::cloud(4, 11);
  std::vector<VolumeParticle> p = c.particles;
  Camera tall = c.camera;
  tall.width = 4;
  tall.height = 2000;
  p.push_back({float(tall.eye.x), float(tall.eye.y), float(tall.eye.z - 1), 5000.0f, 1e-12f, 1});
  VolumeOptions o = test::cloud_options(VolumeMode::dvr, c.spacing);
  o.sampling = 16;
  VolumeCaster caster;
  VolumeFrame f;
  try {
    caster.run(tall, p, o, f);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("coarsen `sampling` or move the camera"),
              std::string::npos)
        << e.what();
  }
}

// Adaptive sampling (DVR, Shepard) on the broken and degenerate inputs above: finite, bad
// particles counted, and with relax 0 within the tolerance of the full-rate frame.
TEST(StabilityVolume, AdaptiveSamplingHoldsOnBadAndDegenerateInput) {
  const test::Cloud c = test::cloud(6, 5);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<VolumeParticle> dirty = c.particles;
  dirty.insert(dirty.begin() + 3, {nan, 0, 0, 0.1f, 0.5f, 1});
  dirty.push_back({0, 0, 0, 0.1f, 0.5f, nan});
  std::vector<VolumeParticle> one_point(c.particles.size(), c.particles.front());
  const glm::dvec3 mid(0.25, 0.25, 0.25);
  const std::vector<std::pair<std::vector<VolumeParticle>, Camera>> inputs = {
      {dirty, c.camera},
      {{}, c.camera},
      {{c.particles.front()}, c.camera},
      {one_point, c.camera},
      {c.particles, test::look_at(mid, mid + glm::dvec3(0, 0, -1), 40, 30, 60)}};
  for (const auto& [particles, camera] : inputs)
    for (double relax : {0.0, 1.0}) {
      VolumeOptions o = test::cloud_options(VolumeMode::dvr, c.spacing);
      VolumeCaster caster;
      VolumeFrame exact, adaptive;
      caster.run(camera, particles, o, exact);
      o.adaptive = {0.004, relax};
      const VolumeCounts counts = caster.run(camera, particles, o, adaptive);
      expect_finite(adaptive);
      EXPECT_EQ(counts.particles_invalid, &particles == &inputs.front().first ? 2 : 0);
      if (relax > 0) continue;
      for (std::size_t i = 0; i < exact.picture.rgba.size(); ++i)
        ASSERT_NEAR(adaptive.picture.rgba[i], exact.picture.rgba[i], 0.004 + 1e-6);
    }
}

}  // namespace
}  // namespace voxspan
