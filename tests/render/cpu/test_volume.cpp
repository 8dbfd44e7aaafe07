// The volume renderer on the CPU (render/cpu/volume_caster.h) against the exact reference at its
// own samples (render/reference/volume_reference.h) and against what is known in closed form:
//   - one particle seen through an absorption-only transfer function: the transmittance is the
//     exponential of the integral along the ray, computed here by quadrature, for every kernel;
//   - one particle's iso surface of its plain sum is the sphere of the radius where the kernel
//     takes the iso value;
//   - a Shepard-normalised block of particles is flat inside;
//   - the picture does not depend on the number of threads, nor on occlusion culling.
// Broken input (NaN particles, no particle, every scale): tests/stability/test_volume.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "render/cpu/volume_caster.h"
#include "render/reference/volume_reference.h"
#include "render/sph_kernel.h"
#include "tests/support/volume_cloud.h"
#include "tools/scenes/scenes.h"
#include "tests/support/image_difference.h"

namespace voxspan {
namespace {

// A transfer table: colour `rgb`, opacity rising linearly from 0 at lo to `alpha` at hi.
TransferTable ramp(double lo, double hi, glm::vec3 rgb, float alpha) {
  TransferTable t;
  t.lo = lo;
  t.hi = hi;
  for (int k = 0; k < kTransferEntries; ++k)
    t.rgba[std::size_t(k)] = glm::vec4(rgb, alpha * float(k) / float(kTransferEntries - 1));
  return t;
}

using test::largest_difference;

// Quadrature of f over [a, b], composite Simpson on n (even) intervals.
template <class F> double simpson(F&& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * f(a + i * h);
  return s * h / 3;
}

TEST(VolumeCaster, OneParticleAbsorbsAsTheLineIntegralOfItsKernel) {
  // Plain sum, q = 1, V = 1 (weight 1 / h^3): the field is W(r). Opacity alpha(Q) = c Q over one
  // unit of length: the ray's transmittance is exp(integral of ln(1 - c W(r(s))) ds).
  for (const auto& [name, kernel] : kSphKernelNames) {
    SCOPED_TRACE(name);
    const double h = 0.5;
    const double w0 = kernel_value(kernel, 0, h);  // the field's largest value
    VolumeOptions o;
    o.kernel = kernel;
    o.shepard = false;
    o.background = false;
    o.termination = 0;
    o.anchor = 0.01;
    o.sampling = 2;
    o.transfer = ramp(0, w0, glm::vec3(0), 0.9f);  // opacity 0.9 Q / w0
    const Camera camera = test::look_at({0, 0, 4}, {0, 0, 0}, 48, 48, 30);
    const std::vector<VolumeParticle> p = {
        {0.0f, 0.0f, 0.0f, float(h), float(1 / (h * h * h)), 1.0f}};
    VolumeCaster caster;
    VolumeFrame frame;
    caster.run(camera, p, o, frame);
    const ViewFrame f(camera);
    const double support = kernel_support(kernel) * h;
    double worst = 0;
    for (int y = 0; y < camera.height; y += 3)
      for (int x = 0; x < camera.width; x += 3) {
        const glm::dvec3 dir = glm::normalize(f.world_ray(x, y));
        const double along = glm::dot(-f.eye, dir), miss2 = glm::dot(f.eye, f.eye) - along * along;
        double expected = 1;
        if (miss2 < support * support) {
          const double half = std::sqrt(support * support - miss2);
          const double log_t = simpson(
              [&](double s) {
                const double r = std::sqrt(miss2 + (s - along) * (s - along));
                return std::log(1 - 0.9 * kernel_value(kernel, r, h) / w0);
              },
              along - half, along + half, 4000);
          expected = std::exp(log_t);
        }
        const double transmittance = 1 - frame.picture.at(x, y).a;
        worst = std::max(worst, std::abs(transmittance - expected));
      }
    std::printf("%-13s largest transmittance error %.2e\n", name.data(), worst);
    EXPECT_LT(worst, 1e-4);
  }
}

TEST(VolumeCaster, OneParticlesIsoSurfaceIsTheSphereWhereTheKernelTakesTheValue) {
  for (const auto& [name, kernel] : kSphKernelNames) {
    SCOPED_TRACE(name);
    const double h = 0.5, spacing = 0.4;
    // The radius where W = iso: bisection on the kernel (decreasing in r).
    const double radius = 0.6 * kernel_support(kernel) * h;
    const double iso = kernel_value(kernel, radius, h);
    VolumeOptions o;
    o.kernel = kernel;
    o.shepard = false;
    o.mode = VolumeMode::iso;
    o.isos = {IsoSurface{iso, {1, 1, 1}, 1}};
    o.anchor = spacing;
    o.transfer = ramp(0, 1, glm::vec3(1), 0);
    const Camera camera = test::look_at({0, 0, 3}, {0, 0, 0}, 64, 64, 40);
    const std::vector<VolumeParticle> p = {
        {0.0f, 0.0f, 0.0f, float(h), float(1 / (h * h * h)), 1.0f}};
    VolumeCaster caster;
    VolumeFrame frame;
    const VolumeCounts counts = caster.run(camera, p, o, frame);
    const ViewFrame f(camera);
    double worst = 0;
    int hits = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const glm::dvec3 dir = glm::normalize(f.world_ray(x, y));
        const double along = glm::dot(-f.eye, dir), miss2 = glm::dot(f.eye, f.eye) - along * along;
        const float d = frame.depth[std::size_t(x) + std::size_t(y) * std::size_t(camera.width)];
        // Rays that graze the sphere within a sample of its edge may cross between samples.
        if (miss2 > 0.98 * radius * radius) continue;
        ++hits;
        ASSERT_GT(d, 0) << x << " " << y;
        worst = std::max(worst, std::abs(d - (along - std::sqrt(radius * radius - miss2))));
      }
    std::printf("%-13s %d hits, largest distance error %.2e spacings\n", name.data(), hits,
                worst / spacing);
    EXPECT_GT(hits, 200);
    EXPECT_GE(counts.iso_hits, hits);
    EXPECT_LT(worst / spacing, 1e-4);
  }
}

TEST(VolumeCaster, AShepardNormalisedBlockIsFlatInside) {
  // A jittered block of particles all of value 2.5: with Shepard the field is 2.5 wherever it is
  // defined, up to the free surface; the renderer sums the same terms as the reference's field
  // (PicturesAreTheReferencesAtTheirSamples).
  const double spacing = 0.1;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02), unit(0, 1);
  std::vector<VolumeParticle> block;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k)
        block.push_back({float(i * spacing + jitter(rng)), float(j * spacing + jitter(rng)),
                         float(k * spacing + jitter(rng)), float(1.3 * spacing),
                         float((1 + 10 * jitter(rng)) / std::pow(1.3, 3)), 2.5f});
  VolumeOptions o;
  o.anchor = spacing;
  double worst = 0;
  int defined = 0;
  for (int n = 0; n < 4000; ++n) {
    const glm::dvec3 x(-0.2 + 1.3 * unit(rng), -0.2 + 1.3 * unit(rng), -0.2 + 1.3 * unit(rng));
    const FieldValue f = volume_field(block, o, x);
    if (!f.defined) continue;
    ++defined;
    worst = std::max(worst, std::abs(f.q - 2.5));
  }
  std::printf("%d defined points of 4000, largest departure from 2.5: %.2e\n", defined, worst);
  EXPECT_GT(defined, 2000);
  EXPECT_LT(worst, 1e-6);
}

TEST(VolumeCaster, PicturesAreTheReferencesAtTheirSamples) {
  const test::Cloud c = test::cloud(9, 7);
  test::each_mode(c.spacing, [&](const VolumeOptions& o) {
    VolumeCaster caster;
    VolumeFrame mine, reference;
    const VolumeCounts counts = caster.run(c.camera, c.particles, o, mine);
    const VolumeCounts exact = volume_reference(c.camera, c.particles, o, reference);
    const double d = largest_difference(mine.picture, reference.picture);
    std::printf("%-5s shepard %d: largest channel difference %.2e; samples %lld, hits %lld\n",
                name_of(kVolumeModeNames, o.mode).data(), int(o.shepard), d,
                static_cast<long long>(counts.samples), static_cast<long long>(counts.iso_hits));
    EXPECT_LT(d, 1e-5);
    EXPECT_EQ(counts.samples, exact.samples);
    EXPECT_EQ(counts.iso_hits, exact.iso_hits);
    EXPECT_GT(counts.samples, 1000);
    if (o.mode != VolumeMode::dvr) {
      EXPECT_GT(counts.iso_hits, 100);
      for (std::size_t i = 0; i < mine.depth.size(); ++i)
        EXPECT_NEAR(mine.depth[i], reference.depth[i], 1e-5 * reference.depth[i] + 1e-7);
    }
  });
}

TEST(VolumeCaster, EveryKernelIsTheReferences) {
  const test::Cloud c = test::cloud(7, 8);
  test::each_kernel(c.spacing, [&](const VolumeOptions& o, std::string_view) {
    VolumeCaster caster;
    VolumeFrame mine, reference;
    caster.run(c.camera, c.particles, o, mine);
    volume_reference(c.camera, c.particles, o, reference);
    EXPECT_LT(largest_difference(mine.picture, reference.picture), 1e-5);
  });
}

TEST(VolumeCaster, ThePictureDoesNotDependOnTheThreads) {
  const test::Cloud c = test::cloud(10, 3);
  test::expect_same_on_any_threads(c, test::cloud_options(VolumeMode::mixed, c.spacing));
}

TEST(VolumeCaster, OcclusionCullingChangesNoPixel) {
  // An opaque cloud (opacity 0.9 per spacing): tiles whose rays all stop leave their supports
  // behind unwalked. Against every ray stopping on its own (culling off): the same pictures and
  // depths bit for bit, in every mode and with adaptive sampling.
  const test::Cloud c = test::cloud(14, 5);
  Camera camera = c.camera;
  camera.width = 160;
  camera.height = 120;
  std::vector<VolumeOptions> cases;
  for (VolumeMode mode : {VolumeMode::dvr, VolumeMode::iso, VolumeMode::mixed}) {
    VolumeOptions o = test::cloud_options(mode, c.spacing);
    for (glm::vec4& e : o.transfer.rgba) e.a = 0.9f;
    cases.push_back(o);
  }
  cases.push_back(cases.front());
  cases.back().adaptive = {0.01, 1};
  for (const VolumeOptions& o : cases) {
    SCOPED_TRACE(std::string(name_of(kVolumeModeNames, o.mode)) +
                 (o.adaptive.error_tolerance > 0 ? " adaptive" : ""));
    VolumeCaster caster;
    VolumeFrame with, without;
    const VolumeCounts on = caster.run(camera, c.particles, o, with);
    caster.set_tile_culling(false);
    const VolumeCounts off = caster.run(camera, c.particles, o, without);
    std::printf(
        "%-5s: %lld tiles culled, %lld supports not walked; evaluations %lld against %lld\n",
        name_of(kVolumeModeNames, o.mode).data(), static_cast<long long>(on.tiles_culled),
        static_cast<long long>(on.supports_culled), static_cast<long long>(on.kernel_evaluations),
        static_cast<long long>(off.kernel_evaluations));
    EXPECT_EQ(with.picture.rgba, without.picture.rgba);
    EXPECT_EQ(with.depth, without.depth);
    EXPECT_EQ(on.samples, off.samples);
    EXPECT_EQ(on.rays_stopped, off.rays_stopped);
    EXPECT_EQ(on.iso_hits, off.iso_hits);
    EXPECT_EQ(off.tiles_culled + off.supports_culled, 0);
    // A stopped ray takes no kernel already: what culling saves is walking the supports.
    EXPECT_EQ(on.kernel_evaluations, off.kernel_evaluations);
    EXPECT_GT(on.tiles_culled, 0);
    EXPECT_GT(on.supports_culled, 0);
  }
}

TEST(VolumeCaster, TheConvergedIntegralIsCloseAtTheDefaultSampling) {
  // A plain sum of positive values through a transfer function with no opacity at 0, so that the
  // integrand is continuous where the field starts: the samples converge at second order. (With
  // Shepard the field starts at its weight floor with a jump, and converges at first order
  // there: docs/benchmarks.md.)
  test::Cloud c = test::cloud(7, 11);
  for (VolumeParticle& p : c.particles) p.value += 1.5f;
  VolumeOptions o = test::cloud_options(VolumeMode::dvr, c.spacing);
  o.shepard = false;
  o.termination = 0;  // where a ray stops moves with the samples
  o.transfer.lo = 0;
  o.transfer.hi = 4;
  for (int k = 0; k < kTransferEntries; ++k) o.transfer.rgba[std::size_t(k)].a *= float(k) / 255;
  int doublings = 0;
  const VolumeFrame converged = converged_volume(c.camera, c.particles, o, 1e-4, 6, &doublings);
  VolumeCaster caster;
  VolumeFrame frame;
  caster.run(c.camera, c.particles, o, frame);
  const double d = largest_difference(frame.picture, converged.picture);
  std::printf("converged after %d doublings; at sampling 1 the largest difference is %.3g\n",
              doublings, d);
  EXPECT_LT(doublings, 6);
  EXPECT_LT(d, 0.01);
}

}  // namespace
}  // namespace voxspan
