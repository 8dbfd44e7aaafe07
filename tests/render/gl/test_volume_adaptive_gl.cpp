// Adaptive sampling on the GL volume renderer (render/gl/passes/volume_march.h following the
// plans of render/cpu/volume_adaptive.h): with relax 0 no pixel of the GL picture moves from the
// GL full-rate picture by more than the tolerance (1e-6 of slack for rounding), on the scenes of
// the CPU's test (tests/render/cpu/test_volume_adaptive.cpp); and the GL adaptive picture is the
// CPU caster's adaptive one to float sums' rounding, with super-pixels (relax 0) and with coarse
// cells (relax 1), where that picture lies far from the full rate's: a march that ignored the
// plans, took the wrong samples or let one stand for the wrong length would miss it. Past
// llvmpipe's loop budget the adaptive frame is the caster's.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "gl_fixture.h"
#include "render/cpu/volume_caster.h"
#include "render/gl/info.h"
#include "render/gl/volume_renderer.h"
#include "tools/scenes/adaptive_scenes.h"
#include "tests/support/image_difference.h"
#include "tests/support/sanitizers.h"

namespace voxspan {
namespace {

using test::largest_difference;

constexpr double kRounding = 1e-6;  // the float compositing's slack over the tolerance
// The GL march's float sums against the caster's double ones (tests/render/gl/test_volume_gl.cpp).
constexpr double kFloatSums = 1e-4;
// The CPU test's scenes with fewer particles, within llvmpipe's loop budget and time.
constexpr int kWidth = 160, kHeight = 100;
std::vector<test::AdaptiveScene> scenes() {
  return test::adaptive_scenes(kWidth, kHeight, 0.04, 10);
}

// The scene's frame under `o` on the GL renderer into `out`.
VolumeCounts render_gl(const test::AdaptiveScene& scene, const VolumeOptions& o, VolumeFrame& out) {
  test::context();
  static const std::unique_ptr<VolumeRenderer> renderer = make_gl_volume_renderer(test::shaders());
  Recorder recorder;
  return renderer->render(scene.camera, scene.particles, o, recorder, out);
}

// The scene under `adaptive` on GL against GL's full rate and the caster's adaptive frame;
// the GL frame's counts.
struct Against {
  double full_rate = 0;    // GL adaptive against GL full rate
  double caster = 0;       // GL adaptive against the caster's adaptive
  double caster_full = 0;  // the caster's adaptive against its full rate
};
VolumeCounts compare(const test::AdaptiveScene& scene, VolumeOptions o, AdaptiveOptions adaptive,
                     Against& out) {
  VolumeFrame gl_full, gl, cpu_full, cpu;
  EXPECT_EQ(render_gl(scene, o, gl_full).gl_frames_on_cpu, 0);  // the GL march's, not the caster's
  VolumeCaster caster;
  caster.run(scene.camera, scene.particles, o, cpu_full);
  o.adaptive = adaptive;
  const VolumeCounts counts = render_gl(scene, o, gl);
  EXPECT_EQ(counts.gl_frames_on_cpu, 0);
  const VolumeCounts cpu_counts = caster.run(scene.camera, scene.particles, o, cpu);
  out = {largest_difference(gl.picture, gl_full.picture),
         largest_difference(gl.picture, cpu.picture),
         largest_difference(cpu.picture, cpu_full.picture)};
  std::printf(
      "%-32s tolerance %.3f relax %g: against GL full rate %.2e, the caster's %.2e (its own "
      "full rate %.2e); cells %lld coarse %lld super-pixel (caster %lld, %lld), skipped %lld\n",
      scene.name.c_str(), adaptive.error_tolerance, adaptive.relax, out.full_rate, out.caster,
      out.caster_full, static_cast<long long>(counts.cells_coarse),
      static_cast<long long>(counts.cells_super_pixel),
      static_cast<long long>(cpu_counts.cells_coarse),
      static_cast<long long>(cpu_counts.cells_super_pixel),
      static_cast<long long>(counts.samples_skipped));
  return counts;
}

TEST(VolumeAdaptiveGl, NoPixelMovesFromTheGlFullRateByMoreThanTheTolerance) {
  std::int64_t skipped = 0, super_pixels = 0;
  double far_from_full_rate = 0;  // how far the caster's adaptive pictures moved, at most
  // Under the sanitizers one tolerance (a third of the frames); Release runs all three.
  const std::vector<double> tolerances =
      test::kUnderSanitizers ? std::vector<double>{0.004} : std::vector<double>{0.001, 0.004, 0.01};
  for (const test::AdaptiveScene& scene : scenes())
    for (bool background : {true, false})
      for (double tolerance : tolerances) {
        SCOPED_TRACE(scene.name + (background ? ", sky" : ", no background") + ", tolerance " +
                     std::to_string(tolerance));
        VolumeOptions o = scene.options;
        o.background = background;
        Against d;
        const VolumeCounts c = compare(scene, o, {tolerance, 0}, d);
        EXPECT_LE(d.full_rate, tolerance + kRounding);
        EXPECT_LE(d.caster, kFloatSums);
        skipped += c.samples_skipped;
        super_pixels += c.cells_super_pixel;
        far_from_full_rate = std::max(far_from_full_rate, d.caster_full);
      }
  // Something skipped, and adaptive pictures far enough from the full rate's that a GL march
  // ignoring the plans would not pass for the caster's.
  EXPECT_GT(skipped, 0);
  EXPECT_GT(super_pixels, 0);
  EXPECT_GT(far_from_full_rate, 10 * kFloatSums);
}

TEST(VolumeAdaptiveGl, CoarseCellsAreTheCastersSampleForSample) {
  // relax 1 chooses coarse cells (test::slope_ramp: only those); along the ramp a coarse
  // sample's value is its run's, so a sample standing for the wrong length shows there.
  for (const test::AdaptiveScene& scene :
       {test::slope_ramp(kWidth, kHeight, 12, 14), scenes().back()}) {
    SCOPED_TRACE(scene.name);
    Against d;
    const VolumeCounts c = compare(scene, scene.options, {0.004, 1}, d);
    EXPECT_GT(c.cells_coarse, 20);
    EXPECT_GT(c.samples_skipped, 0);
    EXPECT_LE(d.caster, kFloatSums);
  }
}

// llvmpipe ends an invocation's loops silently after 65535 passes: an adaptive frame whose
// bundles would run past that is the caster's adaptive frame, counted, skipped samples and all.
TEST(VolumeAdaptiveGl, PastTheSoftwareLoopBudgetTheFrameIsTheCasters) {
  test::context();
  if (!gl::software_renderer()) GTEST_SKIP() << "a GPU has no loop budget";
  const test::AdaptiveScene scene = test::radial_scene(kWidth, kHeight, 20);
  VolumeOptions o = scene.options;
  o.adaptive = {0.05, 0};
  VolumeFrame gl, cpu;
  const VolumeCounts counts = render_gl(scene, o, gl);
  const VolumeCounts cpu_counts = VolumeCaster().run(scene.camera, scene.particles, o, cpu);
  EXPECT_EQ(counts.gl_frames_on_cpu, 1);
  EXPECT_EQ(counts.samples_skipped, cpu_counts.samples_skipped);
  EXPECT_GT(counts.samples_skipped, 0);
  EXPECT_EQ(gl.picture.rgba, cpu.picture.rgba);
}

}  // namespace
}  // namespace voxspan
