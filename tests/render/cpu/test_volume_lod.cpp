// Particle level of detail (render/cpu/volume_lod.h) against the same frames without it:
//   - a cloud far away, every particle's h under half a pixel: at level 1 about a hundredth of
//     the particles are drawn, and the picture is within a measured bound of the one drawn from
//     every particle (the silhouette grows by about a pixel; inside it the field is smoothed
//     over a cell);
//   - a cloud near, every support over many samples: nothing merged, the picture bit for bit;
//   - broken particles (NaN, infinite, h or weight <= 0) are counted invalid as without level
//     of detail and change no pixel;
//   - the merged picture does not depend on the threads, and adaptive sampling keeps its
//     tolerance on it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "render/cpu/volume_caster.h"
#include "tests/support/image_difference.h"
#include "tests/support/volume_cloud.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

using test::largest_difference;

// A block of 40^3 particles (h = 1.3 spacings, 0.13) seen from 40 units away at 96x72 pixels:
// a pixel is 0.3 units there, h under half of one.
test::Cloud far_cloud() {
  test::Cloud c = test::cloud(40, 17);
  const double mid = 0.5 * 39 * c.spacing;
  c.camera = test::look_at({mid + 8, mid + 10, mid + 38}, {mid, mid, mid}, 96, 72, 30);
  return c;
}

VolumeOptions with_lod(VolumeOptions o, double level) {
  o.level_of_detail = level;
  return o;
}

// The largest channel difference over the pixels whose 3x3 neighbourhood is all fluid (the
// opacity reached 0.5: depth > 0) in `a`: away from the silhouette.
double inner_difference(const VolumeFrame& a, const VolumeFrame& b) {
  const int w = a.picture.width, h = a.picture.height;
  const auto fluid = [&](int x, int y) { return a.depth[std::size_t(x + w * y)] > 0; };
  double d = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      bool inner = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inner = inner && fluid(x + dx, y + dy);
      if (!inner) continue;
      for (std::size_t c = 0; c < 4; ++c) {
        const std::size_t i = 4 * std::size_t(x + w * y) + c;
        d = std::max(d, double(std::abs(a.picture.rgba[i] - b.picture.rgba[i])));
      }
    }
  return d;
}

TEST(VolumeLod, FarSmallParticlesAreMergedWithinABoundOfThePictureOfAll) {
  const test::Cloud c = far_cloud();
  for (VolumeMode mode : {VolumeMode::dvr, VolumeMode::mixed}) {
    const VolumeOptions o = test::cloud_options(mode, c.spacing);
    VolumeCaster caster;
    VolumeFrame all, merged;
    const VolumeCounts off = caster.run(c.camera, c.particles, o, all);
    const VolumeCounts on = caster.run(c.camera, c.particles, with_lod(o, 1), merged);
    const double p99 = test::difference_quantile(all.picture, merged.picture, 0.99);
    const double inner = inner_difference(all, merged);
    std::printf(
        "%-5s: %lld particles, %lld merged into %lld; evaluations %lld against %lld; channel "
        "difference largest %.3g, p99 %.3g, inside the silhouette %.3g\n",
        name_of(kVolumeModeNames, mode).data(), static_cast<long long>(on.particles),
        static_cast<long long>(on.particles_merged), static_cast<long long>(on.particles_coarse),
        static_cast<long long>(on.kernel_evaluations),
        static_cast<long long>(off.kernel_evaluations),
        largest_difference(all.picture, merged.picture), p99, inner);
    EXPECT_EQ(on.particles, off.particles);
    EXPECT_EQ(on.particles_merged, on.particles);  // every h is under a pixel
    EXPECT_LT(on.particles_coarse * 50, on.particles);
    EXPECT_LT(on.kernel_evaluations, off.kernel_evaluations);
    EXPECT_EQ(off.particles_merged + off.particles_coarse, 0);
    // Measured: p99 0.053 in both modes; inside 0.23 (DVR: the field's sin(3x), 7 pixels a
    // period, smoothed over cells of 1.7 pixels) and 0.42 (mixed: iso crossings moved with it).
    EXPECT_LT(p99, 0.07);
    EXPECT_LT(inner, mode == VolumeMode::dvr ? 0.3 : 0.5);
  }
}

TEST(VolumeLod, SupportsOverManySamplesAreDrawnAsTheyAre) {
  const test::Cloud c = test::cloud(10, 4);  // h = 0.13 spans about 4 pixels
  for (VolumeMode mode : {VolumeMode::dvr, VolumeMode::iso, VolumeMode::mixed}) {
    const VolumeOptions o = test::cloud_options(mode, c.spacing);
    VolumeCaster caster;
    VolumeFrame all, merged;
    const VolumeCounts off = caster.run(c.camera, c.particles, o, all);
    const VolumeCounts on = caster.run(c.camera, c.particles, with_lod(o, 1), merged);
    EXPECT_EQ(on.particles_merged + on.particles_coarse, 0);
    EXPECT_EQ(merged.picture.rgba, all.picture.rgba);
    EXPECT_EQ(merged.depth, all.depth);
    EXPECT_EQ(on.samples, off.samples);
  }
}

TEST(VolumeLod, BrokenParticlesAreCountedAndChangeNoPixel) {
  const test::Cloud c = far_cloud();
  const VolumeOptions o = with_lod(test::cloud_options(VolumeMode::mixed, c.spacing), 1);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<VolumeParticle> broken = c.particles;
  const VolumeParticle& p = c.particles[100];
  const std::vector<VolumeParticle> bad = {
      {nan, p.y, p.z, p.h, p.weight, p.value}, {p.x, p.y, inf, p.h, p.weight, p.value},
      {p.x, p.y, p.z, 0, p.weight, p.value},   {p.x, p.y, p.z, -p.h, p.weight, p.value},
      {p.x, p.y, p.z, p.h, -1, p.value},       {p.x, p.y, p.z, p.h, p.weight, nan}};
  for (std::size_t k = 0; k < bad.size(); ++k)
    broken.insert(broken.begin() + std::ptrdiff_t(1000 * k), bad[k]);
  VolumeCaster caster;
  VolumeFrame clean, with_broken, without_lod;
  const VolumeCounts good = caster.run(c.camera, c.particles, o, clean);
  const VolumeCounts on = caster.run(c.camera, broken, o, with_broken);
  VolumeOptions off = o;
  off.level_of_detail = 0;
  const VolumeCounts plain = caster.run(c.camera, broken, off, without_lod);
  EXPECT_EQ(on.particles_invalid, std::int64_t(bad.size()));
  EXPECT_EQ(on.particles_invalid, plain.particles_invalid);
  EXPECT_EQ(on.particles, good.particles + std::int64_t(bad.size()));
  EXPECT_EQ(on.particles_merged, good.particles_merged);
  EXPECT_EQ(on.particles_coarse, good.particles_coarse);
  EXPECT_EQ(with_broken.picture.rgba, clean.picture.rgba);
  EXPECT_THROW(caster.run(c.camera, c.particles, with_lod(o, -1), clean), Error);
  EXPECT_THROW(caster.run(c.camera, c.particles, with_lod(o, nan), clean), Error);
}

TEST(VolumeLod, ThePictureDoesNotDependOnTheThreads) {
  const test::Cloud c = far_cloud();
  test::expect_same_on_any_threads(c,
                                   with_lod(test::cloud_options(VolumeMode::mixed, c.spacing), 2));
}

TEST(VolumeLod, AdaptiveSamplingKeepsItsToleranceOnTheMergedParticles) {
  // The guarantee of render/cpu/volume_adaptive.h holds against the full-rate frame of the
  // particles marched: here the merged ones.
  const test::Cloud c = far_cloud();
  VolumeOptions o = with_lod(test::cloud_options(VolumeMode::dvr, c.spacing), 1);
  VolumeCaster caster;
  VolumeFrame full_rate, adaptive;
  caster.run(c.camera, c.particles, o, full_rate);
  o.adaptive = {0.01, 0};
  const VolumeCounts counts = caster.run(c.camera, c.particles, o, adaptive);
  EXPECT_GT(counts.particles_merged, 0);
  EXPECT_LT(largest_difference(adaptive.picture, full_rate.picture), 0.01 + 1e-6);
}

}  // namespace
}  // namespace voxspan
