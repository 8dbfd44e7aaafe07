// The stability suite's frames that are hard for what they hold rather than for their shape:
// scenes from 1e-12 to 1e12 world units (the same picture as at unit scale), past 1e18
// (refused by the renderers, rendered in their own units by the views' renderers from 1e-30 to
// 1e36, refused past 1e38), NaN and infinite particles (left out, counted, the picture that of the
// clean particles), an empty frame (the environment alone, no spans, no error), and through the
// public Adapter a particle count that changes every step (each step's picture right, nothing
// kept from the step before, nothing growing) and a refused step. Both renderers each time
// (stability_fixture.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "render/gl/voxelizer.h"
#include "stability_fixture.h"
#include "tools/scenes/image_compare.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

// A dam break a little after release (a front, a thin tongue and spray) at `scale` world
// units: positions, radii, camera, gap bridging, filter radius and the shading's lengths all
// scaled alike, so the picture must not change.
test::Scene dam_break_at(double scale) {
  test::DamBreak shape;
  shape.spacing = 0.04;
  shape.radius = 0.04;
  shape.spray_fraction = 0.02;
  test::Scene s;
  s.name = "dam break at scale " + std::to_string(scale);
  for (ParticleSphere p : test::dam_break(shape, 0.2, 3)) {
    p.x = float(p.x * scale), p.y = float(p.y * scale), p.z = float(p.z * scale);
    p.radius = float(p.radius * scale);
    s.particles.push_back(p);
  }
  s.camera = test::look_at(glm::dvec3{0.6, 0.9, -1.3} * scale, glm::dvec3{0.6, 0.2, 0.15} * scale,
                           160, 120);
  s.scale = scale;
  s.ground_height = 0;
  s.voxelize.gap_bridging = shape.spacing * scale;
  s.voxelize.grid.alpha_degrees = 3;
  s.surfaces.filter_radius = 2 * shape.radius * scale;
  return s;
}

// The least PSNR of a picture against the unit scene's, where only float rounding differs. A
// refracted ray turns with the normals at the surface's edges, where the filter fits a line to
// one side (render/model/surface_filter.glsl): its weights there are partly negative, so the
// rounding grows a few times on its way into the picture: measured 49.6 to 55 dB refractive
// (57 to 73 with the one-sided mean the filter took before), 85 to 96 dB in the other modes. A
// scale bug shows far lower (25 dB: the normals' cross product out of float's range).
double least_psnr(ShadeMode mode) { return mode == ShadeMode::refractive ? 45.0 : 50.0; }

// At 1e-6 and 1e6 world units (and 1e-12 and 1e12, past where the Sobel normals' cross
// product of world lengths used to under- and overflow floats: 25 dB then) the spans keep
// their bounds against the reference, and the pictures, mode by mode and renderer by renderer,
// match the unit scene's within a PSNR bound: only float rounding differs, so nothing
// scale-dependent (an absolute epsilon, a fixed near distance) may show (least_psnr).
TEST(Stability, ScenesAtTinyAndHugeScales) {
  const test::Checked unit = test::check_both(dam_break_at(1));
  for (double scale : {1e-12, 1e-6, 1e6, 1e12}) {
    SCOPED_TRACE(scale);
    const test::Checked c = test::check_both(dam_break_at(scale));
    for (std::size_t m = 0; m < test::kModes.size(); ++m) {
      const double gl = test::compare_images(c.gl.images[m], unit.gl.images[m]).psnr;
      const double cpu = test::compare_images(c.cpu.images[m], unit.cpu.images[m]).psnr;
      std::printf("scale %g, %-11s: PSNR against unit scale GL %.1f dB, CPU %.1f dB\n", scale,
                  shade_mode_name(test::kModes[m]), gl, cpu);
      EXPECT_GE(gl, least_psnr(test::kModes[m])) << shade_mode_name(test::kModes[m]);
      EXPECT_GE(cpu, least_psnr(test::kModes[m])) << shade_mode_name(test::kModes[m]);
    }
  }
}

// `render` throws voxspan::Error saying `why`.
template <class F> void expect_refused(F render, const std::string& why) {
  try {
    render();
    ADD_FAILURE() << "rendered, not refused: " << why;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
  }
}

// Past the float range of the passes after the grid (they square view-space lengths: about
// 1e19 units) the GL renderer used to draw nothing, every sphere counted visible, and the CPU
// renderer shaded at 34 dB. The renderers themselves refuse such a frame, naming its depth,
// its counts still in the stats; 1e16 still draws as at unit scale. The views' renderers
// (make_surface_renderer) render it in its own units instead (the next case).
TEST(Stability, FramesBeyondTheFloatRangeAreRefused) {
  const test::Scene deep = dam_break_at(1e20);
  for (bool gl : {true, false}) {
    SCOPED_TRACE(gl ? "GL" : "CPU");
    expect_refused([&] { gl ? test::render_gl(deep) : test::render_cpu(deep); },
                   "world units from the eye, past 1e+18 times its unit of 1 world units");
  }
  FrameStats stats;
  Recorder recorder(stats);
  EXPECT_THROW(fit_frame(deep.camera, deep.particles, deep.voxelize, recorder), Error);
  EXPECT_EQ(stats.count("particles.visible"), std::int64_t(deep.particles.size()));
  EXPECT_GT(stats.figure("grid.far"), 1e20);

  const test::Checked unit = test::check_both(dam_break_at(1));
  const test::Checked far = test::check_both(dam_break_at(1e16));
  for (std::size_t m = 0; m < test::kModes.size(); ++m) {
    EXPECT_GE(test::compare_images(far.gl.images[m], unit.gl.images[m]).psnr,
              least_psnr(test::kModes[m]));
    EXPECT_GE(test::compare_images(far.cpu.images[m], unit.cpu.images[m]).psnr,
              least_psnr(test::kModes[m]));
  }
}

// The views' renderers render a frame far from unit scale in units of the power of two nearest
// its camera's distance (render/frame_units.h): from 1e-30 to 1e36 world units the pictures,
// mode by mode and renderer by renderer, match the unit scene's as above (least_psnr), and
// what leaves the renderer is in world units: the first-hit distances those of the unit scene
// times the scale (99 % within 1e-5, float rounding of the scaled positions; measured: all on
// the CPU renderer, all but 2 to 4 of 3171 on the GL one, whose splat rounds those few a layer
// the other way), and so the spans' far depth, inside lengths and the grid's figures. Past 1e38
// world units from the eye, where the float span and depth images end, the frame is refused by
// name.
TEST(Stability, ViewsRenderFramesFarFromUnitScaleInTheirOwnUnits) {
  for (RenderBackend backend : {RenderBackend::gl, RenderBackend::cpu}) {
    const char* name = backend == RenderBackend::gl ? "GL" : "CPU";
    SCOPED_TRACE(name);
    const test::Frame unit = test::render_as_view(dam_break_at(1), backend);
    for (double scale : {1e-30, 1e-20, 1e20, 1e30, 1e36}) {
      SCOPED_TRACE(scale);
      const test::Frame f = test::render_as_view(dam_break_at(scale), backend);
      for (std::size_t m = 0; m < test::kModes.size(); ++m) {
        const double psnr = test::compare_images(f.images[m], unit.images[m]).psnr;
        std::printf("%s, scale %g, %-11s: PSNR against unit scale %.1f dB\n", name, scale,
                    shade_mode_name(test::kModes[m]), psnr);
        EXPECT_GE(psnr, least_psnr(test::kModes[m])) << shade_mode_name(test::kModes[m]);
      }
      ASSERT_EQ(f.first_hit.rgba.size(), unit.first_hit.rgba.size());
      std::size_t hits = 0, off = 0, missed = 0;
      double worst = 0;
      for (std::size_t k = 0; k < f.first_hit.rgba.size(); k += 4) {
        const double a = f.first_hit.rgba[k] / scale, b = unit.first_hit.rgba[k];
        hits += b > 0;
        missed += (a > 0) != (b > 0);
        if (a > 0 && b > 0) {
          off += std::abs(a - b) > 1e-5 * b;
          worst = std::max(worst, std::abs(a - b) / b);
        }
      }
      std::printf("%s, scale %g: %zu first hits, %zu off by more than 1e-5, worst %.2g\n", name,
                  scale, hits, off, worst);
      EXPECT_GT(hits, 1000u);
      EXPECT_EQ(missed, 0u);
      EXPECT_LE(off, hits / 100);
      EXPECT_LE(worst, 1.01 * unit.spans.grid.k_d());  // a layer: the GL splat's rounding
      EXPECT_EQ(f.spans.spans.size(), unit.spans.spans.size());
      EXPECT_NEAR(f.spans.grid.far() / scale, unit.spans.grid.far(), 1e-5 * unit.spans.grid.far());
      EXPECT_NEAR(f.spans.inside_sum() / scale, unit.spans.inside_sum(),
                  1e-4 * unit.spans.inside_sum());
      EXPECT_NEAR(f.stats.figure("grid.far") / scale, unit.stats.figure("grid.far"),
                  1e-5 * unit.stats.figure("grid.far"));
    }
    expect_refused([&] { test::render_as_view(dam_break_at(1e38), backend); },
                   "past the 1e+38 that its float span and depth images hold");
  }
}

// NaN and infinite coordinates and radii, and a finite position so large that its squares
// overflow: the renderers count the first as particles.invalid and skip them, the other is
// culled; the spans and pictures are exactly those of the clean particles. The classifier
// counts nonfinite positions in ClassifyCounts::dropped_nonfinite (checked through the Adapter
// below).
TEST(Stability, NaNAndInfinitePositionsAreCountedAndLeftOut) {
  test::Scene clean;
  clean.name = "clean cloud";
  clean.particles = test::random_cloud(300, {-1, -1, -1}, {1, 1, 1}, 0.05, 0.12, 21);
  clean.camera = test::frame_scene(clean.particles, {0.2, -0.3, -1}, 96, 64);
  clean.voxelize.grid.alpha_degrees = 2;
  clean.surfaces.filter_radius = 0.05;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  test::Scene dirty = clean;
  dirty.name = "cloud with NaN and inf";
  const ParticleSphere bad[] = {{nan, 0, 0, 0.1f},   {0, inf, 0, 0.1f},       {0, 0, -inf, 0.1f},
                                {0, 0, 0, nan},      {0, 0, 0, inf},          {nan, nan, nan, nan},
                                {inf, -inf, inf, 1}, {0.1f, 0.2f, 0.3f, -inf}};
  std::size_t at = 3;
  for (const ParticleSphere& p : bad)
    dirty.particles.insert(dirty.particles.begin() + at, p), at += 31;
  dirty.particles.push_back({3e38f, -3e38f, 3e38f, 0.1f});
  const test::Checked a = test::check_both(clean);
  const test::Checked b = test::check_both(dirty);
  for (const test::Frame* f : {&b.gl, &b.cpu}) {
    EXPECT_EQ(f->stats.count("particles.invalid"), std::int64_t(std::size(bad)));
    EXPECT_EQ(f->stats.count("particles.visible"), std::int64_t(clean.particles.size()));
  }
  EXPECT_TRUE(test::identical(a.gl.spans, b.gl.spans));
  EXPECT_TRUE(test::identical(a.cpu.spans, b.cpu.spans));
  for (std::size_t m = 0; m < test::kModes.size(); ++m) {
    EXPECT_EQ(a.gl.images[m].rgba, b.gl.images[m].rgba);
    EXPECT_EQ(a.cpu.images[m].rgba, b.cpu.images[m].rgba);
  }
}

// No particle at all, and only particles the camera cannot see: an empty grid, no span, and
// the environment alone (sky and ground), the same on both renderers up to rounding; no error.
TEST(Stability, EmptyFrame) {
  test::Scene none;
  none.name = "empty frame";
  none.camera = test::look_at({0, 1, 5}, {0, 0, 0}, 96, 64);
  none.ground_height = 0;
  test::Scene unseen = none;
  unseen.name = "nothing visible";
  unseen.particles = {{0, 1, 9, 0.5f}, {60, 0, 0, 0.5f}};
  for (const test::Scene* s : {&none, &unseen}) {
    const test::Checked c = test::check_both(*s);
    for (const test::Frame* f : {&c.gl, &c.cpu}) {
      EXPECT_TRUE(f->spans.grid.empty());
      EXPECT_EQ(f->spans.spans.size(), 0u);
    }
    for (std::size_t m = 0; m < test::kModes.size(); ++m) {
      const double psnr = test::compare_images(c.gl.images[m], c.cpu.images[m]).psnr;
      EXPECT_GE(psnr, 50.0) << shade_mode_name(test::kModes[m]);
    }
  }
}

// A pipeline behind the public Adapter that renders each step's boundary particles and cell
// states on both renderers and keeps what the stability checks measured.
class BothRenderers : public Pipeline {
 public:
  explicit BothRenderers(Camera camera) : camera_(camera) {}

  struct Step {
    std::size_t particles = 0, boundary = 0, dropped = 0;
    test::Frame gl, cpu;
    std::int64_t gpu_peak_bytes = 0, gpu_bytes = 0;
  };
  std::vector<Step> steps;

  Status process(const StepData& data, const StepStats& stats) override {
    test::Scene s;
    s.name = "adapter step " + std::to_string(data.step) + ", " +
             std::to_string(stats.counts.particles) + " particles";
    s.particles.assign(data.boundary.begin(), data.boundary.end());
    s.cells = data.cells;
    s.camera = camera_;
    s.voxelize.gap_bridging = 0.05;
    s.voxelize.grid.alpha_degrees = 3;
    s.surfaces.filter_radius = 0.05;
    s.ground_height = -0.05;
    test::Checked c = test::check_both(s);
    Step step{stats.counts.particles,
              stats.counts.boundary,
              stats.counts.dropped_nonfinite,
              std::move(c.gl),
              std::move(c.cpu),
              0,
              0};
    step.gpu_peak_bytes = step.gl.stats.gpu_peak_bytes;
    step.gpu_bytes = step.gl.stats.gpu_bytes;
    std::printf("step %lld: GPU %lld bytes held, %lld at the peak\n",
                static_cast<long long>(data.step), static_cast<long long>(step.gpu_bytes),
                static_cast<long long>(step.gpu_peak_bytes));
    steps.push_back(std::move(step));
    return {};
  }

 private:
  Camera camera_;
};

// An adapter that builds its own grid (spacing 0.05) and renders each step on both renderers
// from one camera: the two Adapter cases' set-up.
AdapterOptions spacing_005() {
  AdapterOptions options;
  options.classify.particle_spacing = 0.05;
  return options;
}
struct AdapterOnBothRenderers {
  Adapter adapter{spacing_005()};
  std::shared_ptr<BothRenderers> pipeline =
      std::make_shared<BothRenderers>(test::look_at({1.6, 0.9, -1.0}, {0.5, 0.3, 0.3}, 96, 64));
  AdapterOnBothRenderers() { adapter.set_pipeline(pipeline); }
};

// The particle count changes every step (a solver adding and removing particles, and steps
// with none at all), through Adapter::execute with a grid the adapter builds: each step's
// classification counts its particles (NaN ones dropped and counted), each picture passes the
// stability checks, and three rounds of the same counts give bit-identical spans and pictures
// (nothing is kept from the step before). The GL renderer resizes its buffers to each step, so
// the GPU memory it holds follows the step's size, and its peak the step before's too (the old
// buffer lives while the new one is made); from the second round on both repeat exactly:
// nothing grows.
TEST(Stability, ParticleCountThatChangesEveryStep) {
  const test::Particles block = test::lattice_block({0, 0, 0}, {20, 12, 12}, 0.05, 0.05);
  const std::size_t counts[] = {1500, 0, 2880, 1, 700, 0, 2000, 37};
  constexpr std::size_t steps = std::size(counts);
  AdapterOnBothRenderers run;
  Adapter& adapter = run.adapter;
  const std::shared_ptr<BothRenderers>& pipeline = run.pipeline;
  std::int64_t step = 0;
  for (int round = 0; round < 3; ++round)
    for (std::size_t n : counts) {
      // Fresh arrays each step, as a solver that reallocates them would pass (null pointers
      // for none); the first particle of the larger steps NaN, to be dropped and counted.
      std::vector<float> x, y, z;
      for (std::size_t i = 0; i < n; ++i) {
        x.push_back(block[i].x), y.push_back(block[i].y), z.push_back(block[i].z);
      }
      if (n > 100) x[0] = std::numeric_limits<float>::quiet_NaN();
      ++step;
      const Status status =
          adapter.execute(step, 0.01 * double(step),
                          ParticleView::soa(x.data(), y.data(), z.data(), n).with_radius(0.05));
      ASSERT_TRUE(status.ok()) << status.message;
      EXPECT_EQ(adapter.last_stats().counts.particles, n);
      EXPECT_EQ(adapter.last_stats().counts.dropped_nonfinite, n > 100 ? 1u : 0u);
    }
  adapter.finish();
  EXPECT_EQ(adapter.failed_steps(), 0);
  EXPECT_EQ(adapter.render_steps(), 3 * std::int64_t(steps));
  ASSERT_EQ(pipeline->steps.size(), 3 * steps);
  std::int64_t peak = 0;
  for (std::size_t k = 0; k < steps; ++k) {
    SCOPED_TRACE(counts[k]);
    const auto& a = pipeline->steps[k];
    EXPECT_EQ(a.particles, counts[k]);
    EXPECT_EQ(a.dropped, counts[k] > 100 ? 1u : 0u);
    EXPECT_LE(a.boundary, counts[k] - a.dropped);
    if (counts[k] <= 1) {
      EXPECT_EQ(a.boundary, counts[k]);  // a lone particle is its cell's boundary
    }
    for (std::size_t round = 1; round < 3; ++round) {
      const auto& b = pipeline->steps[k + round * steps];
      EXPECT_TRUE(test::identical(a.gl.spans, b.gl.spans));
      EXPECT_TRUE(test::identical(a.cpu.spans, b.cpu.spans));
      for (std::size_t m = 0; m < test::kModes.size(); ++m) {
        EXPECT_EQ(a.gl.images[m].rgba, b.gl.images[m].rgba);
        EXPECT_EQ(a.cpu.images[m].rgba, b.cpu.images[m].rgba);
      }
    }
    const auto& second = pipeline->steps[k + steps];
    const auto& third = pipeline->steps[k + 2 * steps];
    EXPECT_EQ(third.gpu_bytes, second.gpu_bytes);
    EXPECT_EQ(third.gpu_peak_bytes, second.gpu_peak_bytes);
    peak = std::max(peak, third.gpu_peak_bytes);
  }
  std::printf("adapter: %lld render steps, GPU peak %.2f MiB\n",
              static_cast<long long>(adapter.render_steps()), double(peak) / (1 << 20));
}

// A step the renderers refuse (a copy of the fluid 1e20 world units away, past the float
// range) through the Adapter: a clear error status naming the depth, counted in failed_steps,
// the grid the adapter builds over both copies bounded, and the next step renders as before.
TEST(Stability, RefusedStepThroughTheAdapterIsCountedAndTheNextRenders) {
  const test::Particles block = test::lattice_block({0, 0, 0}, {10, 6, 6}, 0.05, 0.05);
  AdapterOnBothRenderers run;
  Adapter& adapter = run.adapter;
  const std::shared_ptr<BothRenderers>& pipeline = run.pipeline;
  std::vector<float> x, y, z;
  for (const ParticleSphere& p : block) x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
  const auto view = ParticleView::soa(x.data(), y.data(), z.data(), x.size()).with_radius(0.05);
  // The same block, and a second copy of it moved 1e20 along the view direction.
  std::vector<float> fx = x, fy = y, fz = z;
  for (std::size_t i = 0; i < x.size(); ++i) {
    fx.push_back(x[i] - 1.1e20f * 0.73f), fy.push_back(y[i] - 1.1e20f * 0.34f),
        fz.push_back(z[i] + 1.1e20f * 0.6f);
  }
  const auto far = ParticleView::soa(fx.data(), fy.data(), fz.data(), fx.size()).with_radius(0.05);
  ASSERT_TRUE(adapter.execute(1, 0.0, view).ok());
  const Status refused = adapter.execute(2, 0.1, far);
  EXPECT_EQ(refused.code, StatusCode::pipeline_failed);
  EXPECT_NE(refused.message.find("world units from the eye, past 1e+18 times its unit"),
            std::string::npos)
      << refused.message;
  EXPECT_EQ(adapter.failed_steps(), 1);
  // The grid the adapter built over both copies grew its cells instead of its cell count:
  // 2^20 cells at most for so few particles (it used to take the option's 2^27, about 3 GB of
  // cell arrays and 4 s for this step).
  EXPECT_LE(adapter.last_classification().geometry.cell_count(), std::size_t(1) << 20);
  ASSERT_TRUE(adapter.execute(3, 0.2, view).ok());
  adapter.finish();
  ASSERT_EQ(pipeline->steps.size(), 2u);
  EXPECT_TRUE(test::identical(pipeline->steps[0].gl.spans, pipeline->steps[1].gl.spans));
  EXPECT_EQ(pipeline->steps[0].cpu.images[2].rgba, pipeline->steps[1].cpu.images[2].rgba);
}

}  // namespace
}  // namespace voxspan
