// The GL volume renderer (render/gl/passes/volume_march.h, on llvmpipe here) against the exact
// reference at its samples (render/reference/volume_reference.h): every linear RGBA channel within
// 1e-4 and the iso hits' depths within 1e-4 relative (float sums against double), in every mode,
// with and without Shepard normalisation, every kernel; the same picture from run to run (no
// atomics in the sums); the CPU caster's kernel evaluations, sample for sample; rays ending at
// walls where the caster's end; past llvmpipe's loop budget, the caster's frame.
// (The comparison found the reference leaving out of an iso hit's gradient a particle whose chord
// fell between two samples, which the renderers count: a 4e-4 difference with poly6.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "gl_fixture.h"
#include "render/backdrop.h"
#include "render/cpu/volume_caster.h"
#include "render/gl/info.h"
#include "render/gl/volume_renderer.h"
#include "render/reference/volume_reference.h"
#include "tests/support/volume_cloud.h"
#include "tests/support/image_difference.h"

namespace voxspan {
namespace {

using test::largest_difference;

// The GL renderer's frame of the cloud.
VolumeCounts on_gl(const test::Cloud& c, const VolumeOptions& o, VolumeFrame& out) {
  test::context();
  static const std::unique_ptr<VolumeRenderer> gl = make_gl_volume_renderer(test::shaders());
  Recorder recorder;
  return gl->render(c.camera, c.particles, o, recorder, out);
}

TEST(VolumeGl, PicturesAreTheReferencesAtTheirSamples) {
  const test::Cloud c = test::cloud(9, 7);
  test::each_mode(c.spacing, [&](const VolumeOptions& o) {
    VolumeFrame mine, reference;
    const VolumeCounts counts = on_gl(c, o, mine);
    const VolumeCounts exact = volume_reference(c.camera, c.particles, o, reference);
    EXPECT_EQ(counts.gl_frames_on_cpu, 0);  // drawn by the march, not the caster
    const double d = largest_difference(mine.picture.rgba, reference.picture.rgba);
    std::printf(
        "%-5s shepard %d: largest channel difference %.2e; samples %lld (reference %lld), hits "
        "%lld (%lld)\n",
        name_of(kVolumeModeNames, o.mode).data(), int(o.shepard), d,
        static_cast<long long>(counts.samples), static_cast<long long>(exact.samples),
        static_cast<long long>(counts.iso_hits), static_cast<long long>(exact.iso_hits));
    EXPECT_LT(d, 1e-4);
    EXPECT_NEAR(double(counts.samples), double(exact.samples), 1e-4 * double(exact.samples));
    if (o.mode == VolumeMode::dvr) return;
    for (std::size_t i = 0; i < mine.depth.size(); ++i)
      EXPECT_NEAR(mine.depth[i], reference.depth[i], 1e-4 * reference.depth[i] + 1e-6) << i;
  });
}

// A log scale (TransferTable::log): the table over log2 q, a value at or under 0 at its first
// entry; the march, the caster and the reference alike, and not the linear picture.
TEST(VolumeGl, OnALogScaleTheMarchAndTheCasterAreTheReference) {
  const test::Cloud c = test::cloud(9, 7);
  VolumeOptions o = test::cloud_options(VolumeMode::dvr, c.spacing);
  o.shepard = true;
  o.transfer.log = true;
  o.transfer.lo = 0.05;  // the cloud's values run from about -1 to 2.5: some at or under 0
  VolumeFrame gl, cpu, reference, linear;
  on_gl(c, o, gl);
  VolumeCaster().run(c.camera, c.particles, o, cpu);
  volume_reference(c.camera, c.particles, o, reference);
  EXPECT_LT(largest_difference(gl.picture.rgba, reference.picture.rgba), 1e-4);
  EXPECT_LT(largest_difference(cpu.picture.rgba, reference.picture.rgba), 1e-4);
  o.transfer.log = false;
  volume_reference(c.camera, c.particles, o, linear);
  EXPECT_GT(largest_difference(linear.picture.rgba, reference.picture.rgba), 0.01);
}

TEST(VolumeGl, RaysEndAtTheWallsWhereTheCastersEnd) {
  // A wall slanting through the cloud (render/backdrop.h), with and without adaptive sampling:
  // the march's picture the caster's, its rays ending at the same samples.
  const test::Cloud c = test::cloud(9, 7);
  Backdrop wall;
  wall.width = c.camera.width;
  wall.height = c.camera.height;
  for (int y = 0; y < wall.height; ++y)
    for (int x = 0; x < wall.width; ++x)
      wall.pixels.push_back(x < wall.width / 5
                                ? glm::vec4(0.1f, 0.2f, 0.7f, Backdrop::kNoWall)
                                : glm::vec4(0.9f, 0.8f, 0.2f, float(2.0 + 0.8 * x / wall.width)));
  for (double tolerance : {0.0, 0.01}) {  // adaptive sampling is DVR's
    VolumeOptions o =
        test::cloud_options(tolerance > 0 ? VolumeMode::dvr : VolumeMode::mixed, c.spacing);
    o.backdrop = &wall;
    o.adaptive = {tolerance, 0};
    VolumeFrame mine, caster_frame;
    EXPECT_EQ(on_gl(c, o, mine).gl_frames_on_cpu, 0);
    VolumeCaster caster;
    const VolumeCounts plain = caster.run(c.camera, c.particles, o, caster_frame);
    const double d = largest_difference(mine.picture.rgba, caster_frame.picture.rgba);
    std::printf("walls, tolerance %.2f: largest channel difference %.2e (%lld samples)\n",
                tolerance, d, static_cast<long long>(plain.samples));
    EXPECT_LT(d, 1e-4);
  }
}

TEST(VolumeGl, EveryKernel) {
  const test::Cloud c = test::cloud(7, 8);
  test::each_kernel(c.spacing, [&](const VolumeOptions& o, std::string_view name) {
    VolumeFrame mine, reference;
    EXPECT_EQ(on_gl(c, o, mine).gl_frames_on_cpu, 0);
    volume_reference(c.camera, c.particles, o, reference);
    const double d = largest_difference(mine.picture.rgba, reference.picture.rgba);
    std::printf("%s: largest channel difference %.2e\n", name.data(), d);
    EXPECT_LT(d, 1e-4);
  });
}

// With no early termination the march evaluates the caster's kernels, sample for sample (with
// it, the caster stops a ray's support at the sample where it became opaque, the GL march at the
// end of that slab).
TEST(VolumeGl, TheCastersKernelEvaluations) {
  const test::Cloud c = test::cloud(9, 7);
  VolumeOptions o = test::cloud_options(VolumeMode::mixed, c.spacing);
  o.termination = 0;
  VolumeFrame mine, cpu;
  const VolumeCounts counts = on_gl(c, o, mine);
  EXPECT_EQ(counts.gl_frames_on_cpu, 0);
  EXPECT_EQ(counts.kernel_evaluations,
            VolumeCaster().run(c.camera, c.particles, o, cpu).kernel_evaluations);
}

TEST(VolumeGl, TheSamePictureFromRunToRun) {
  const test::Cloud c = test::cloud(10, 3);
  const VolumeOptions o = test::cloud_options(VolumeMode::mixed, c.spacing);
  VolumeFrame first, second;
  EXPECT_EQ(on_gl(c, o, first).gl_frames_on_cpu, 0);
  on_gl(c, o, second);
  EXPECT_EQ(first.picture.rgba, second.picture.rgba);
  EXPECT_EQ(first.depth, second.depth);
}

// llvmpipe ends an invocation's loops silently after 65535 passes: a frame whose bundles would
// run past that is the CPU caster's, counted, never a picture with holes.
TEST(VolumeGl, PastTheSoftwareLoopBudgetTheFrameIsTheCasters) {
  test::context();
  if (!gl::software_renderer()) GTEST_SKIP() << "a GPU has no loop budget";
  const test::Cloud c = test::cloud(22, 4);
  VolumeOptions o = test::cloud_options(VolumeMode::iso, c.spacing);
  o.termination = 0;
  VolumeFrame mine, cpu;
  EXPECT_EQ(on_gl(c, o, mine).gl_frames_on_cpu, 1);
  VolumeCaster().run(c.camera, c.particles, o, cpu);
  EXPECT_EQ(mine.picture.rgba, cpu.picture.rgba);
  EXPECT_EQ(mine.depth, cpu.depth);
}

}  // namespace
}  // namespace voxspan
