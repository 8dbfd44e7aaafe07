// The Adapter entry point: trigger, stats, pipeline hand-off, and never throwing into the
// solver.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <stdexcept>

#include "tests/sim_adapter/particle_sets.h"
#include "tests/support/allocation_counter.h"
#include "tests/support/log_capture.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

using test::Point;

AdapterOptions every(std::int64_t n) {
  AdapterOptions o;
  o.render_every = n;
  o.classify.particle_spacing = 1.0;
  return o;
}

struct Recorder : Pipeline {
  std::vector<std::int64_t> steps;
  std::size_t boundary = 0, cells = 0, attribute_values = 0;
  bool skip_odd = false, throw_on_process = false;

  bool wants_step(std::int64_t step, double) override { return !(skip_odd && step % 2); }
  Status process(const StepData& d, const StepStats& s) override {
    if (throw_on_process) throw std::runtime_error("disk full");
    steps.push_back(d.step);
    boundary = d.boundary.size();
    cells = d.cells.cell_count();
    attribute_values = d.attributes.empty() ? 0 : d.attributes[0].values.size();
    EXPECT_EQ(s.counts.boundary, d.boundary.size());
    EXPECT_EQ(d.particles->size(), s.counts.particles);
    return {};
  }
};

// Silences the expected error lines of these tests.
struct QuietLog {
  QuietLog() {
    set_log_sink([](LogLevel, std::string_view) {});
  }
  ~QuietLog() { set_log_sink({}); }
};

TEST(Adapter, RendersEveryNthStepAndKeepsStats) {
  std::vector<Point> pts;
  test::add_lattice(pts, {4, 4, 4}, {16, 16, 16}, 1.0);
  const GridGeometry g = test::cube_grid(2.0, 12);
  const test::SortedGrid s = test::sort_into(g, pts);
  Adapter adapter(every(5));
  auto recorder = std::make_shared<Recorder>();
  adapter.set_pipeline(recorder);
  const auto view = ParticleView::aos(&s.sorted[0].x, s.sorted.size(), sizeof(Point));
  for (int step = 1; step <= 12; ++step)
    EXPECT_TRUE(
        adapter.execute(step, 0.1 * step, view, GridView::offsets(g, s.offsets.data())).ok());
  EXPECT_EQ(recorder->steps, (std::vector<std::int64_t>{5, 10}));
  EXPECT_EQ(adapter.steps_seen(), 12);
  EXPECT_EQ(adapter.render_steps(), 2);
  const StepStats& st = adapter.last_stats();
  EXPECT_EQ(st.step, 10);
  EXPECT_DOUBLE_EQ(st.time, 1.0);
  EXPECT_TRUE(st.rendered);
  EXPECT_EQ(st.counts.particles, pts.size());
  EXPECT_EQ(st.counts.owned, pts.size());
  EXPECT_EQ(st.counts.boundary, 2368u);
  EXPECT_EQ(st.counts.cells_inner_full, 216u);
  EXPECT_EQ(recorder->boundary, 2368u);
  EXPECT_EQ(recorder->cells, 1728u);
  EXPECT_GE(st.seconds_total, st.seconds_classify);
}

TEST(Adapter, PipelineTriggerAndNeverRender) {
  std::vector<Point> pts(3, Point{1, 1, 1});
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  Adapter adapter(every(1));
  auto recorder = std::make_shared<Recorder>();
  recorder->skip_odd = true;
  adapter.set_pipeline(recorder);
  for (int step = 0; step < 6; ++step) adapter.execute(step, 0, view);
  EXPECT_EQ(recorder->steps, (std::vector<std::int64_t>{0, 2, 4}));
  EXPECT_FALSE(adapter.is_render_step(3, 0));

  Adapter never(every(0));
  EXPECT_TRUE(never.execute(0, 0, view).ok());
  EXPECT_EQ(never.render_steps(), 0);
  EXPECT_EQ(never.last_stats().step, -1);
}

TEST(Adapter, NonRenderStepsDoNotTouchTheParticles) {
  // Positions that would crash any read: a non-render step must not look at them.
  const auto view = ParticleView::aos(reinterpret_cast<const float*>(16), 1000000);
  Adapter adapter(every(100));
  const long before = test::allocations();
  int failures = 0;
  for (int step = 1; step < 100; ++step) failures += adapter.execute(step, 0, view).ok() ? 0 : 1;
  EXPECT_EQ(test::allocations(), before) << "a non-render step allocated";
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(adapter.render_steps(), 0);
  // The counter does see the adapter's allocations: a render step makes its buffers.
  std::vector<Point> pts(8, Point{1, 1, 1});
  adapter.execute(100, 0, ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point)));
  EXPECT_GT(test::allocations(), before + 1);
}

TEST(Adapter, BadInputIsAStatusNotAnException) {
  QuietLog quiet;
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {4, 4, 4}, 1.0);
  pts[5].x = std::numeric_limits<float>::quiet_NaN();
  const GridGeometry g = test::cube_grid(2.0, 2);
  test::SortedGrid s = test::sort_into(g, pts);
  AdapterOptions o = every(1);
  o.classify.validate = true;
  Adapter adapter(o);
  const auto view = ParticleView::aos(&s.sorted[0].x, s.sorted.size(), sizeof(Point));

  // NaN: counted and left out, the step succeeds.
  EXPECT_TRUE(adapter.execute(0, 0, view, GridView::offsets(g, s.offsets.data())).ok());
  EXPECT_EQ(adapter.last_stats().counts.dropped_nonfinite, 1u);
  EXPECT_EQ(adapter.last_stats().counts.boundary, 63u);

  // A particle outside its claimed cell.
  std::swap(s.sorted[0], s.sorted.back());
  const Status bad = adapter.execute(1, 0, view, GridView::offsets(g, s.offsets.data()));
  EXPECT_EQ(bad.code, StatusCode::invalid_input);
  EXPECT_NE(bad.message.find("particle 0 at"), std::string::npos) << bad.message;
  EXPECT_EQ(adapter.failed_steps(), 1);
  EXPECT_FALSE(adapter.last_stats().rendered);

  // Zero particles.
  EXPECT_TRUE(adapter.execute(2, 0, ParticleView(), GridView()).ok());
  EXPECT_EQ(adapter.last_stats().counts.particles, 0u);
}

// A grid that holds none of the particles (its origin in other units, a wrong stride) fails the
// step by name; some particles outside it are left out with a warning.
TEST(Adapter, AGridHoldingNoParticleIsAnError) {
  QuietLog quiet;
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {4, 4, 4}, 1.0);
  Adapter adapter(every(1));
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  GridGeometry far = test::cube_grid(2.0, 2);
  far.origin = {1000, 0, 0};
  const Status none = adapter.execute(0, 0, view, GridView::geometry_only(far));
  EXPECT_EQ(none.code, StatusCode::invalid_input);
  EXPECT_NE(none.message.find("none of the 64 particles is in a cell of the grid (2 x 2 x 2 cells "
                              "of 2 from (1000, 0, 0))"),
            std::string::npos)
      << none.message;

  GridGeometry half = test::cube_grid(2.0, 2);
  half.dims[0] = 1;  // x in [0, 2): half the lattice
  EXPECT_TRUE(adapter.execute(1, 0, view, GridView::geometry_only(half)).ok());
  EXPECT_EQ(adapter.last_stats().counts.not_in_grid, 32u);
}

// The solver's cell lists are checked on render steps until one passes, without
// classification.validate_grid: a particle listed in the wrong cell (here, two particles'
// cells swapped) fails the step and says what to check; a grid that matches passes, once.
TEST(Adapter, TheSolversGridIsCheckedUntilItMatches) {
  QuietLog quiet;
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {4, 4, 4}, 1.0);
  const GridGeometry g = test::cube_grid(2.0, 2);
  std::vector<std::uint32_t> cell_of(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) cell_of[i] = test::cell_of(g, pts[i]);
  std::vector<std::uint32_t> swapped = cell_of;
  std::swap(swapped[0], swapped[63]);  // (0.5, 0.5, 0.5) and (3.5, 3.5, 3.5)
  Adapter adapter(every(1));
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  const Status wrong = adapter.execute(0, 0, view, GridView::cell_index(g, swapped.data()));
  EXPECT_EQ(wrong.code, StatusCode::invalid_input);
  EXPECT_NE(wrong.message.find("the solver's grid does not match its particles"), std::string::npos)
      << wrong.message;
  const Status right = adapter.execute(1, 0, view, GridView::cell_index(g, cell_of.data()));
  EXPECT_TRUE(right.ok()) << right.message;
  // Checked once it matched: a later mismatch is the solver's (validate_grid checks always).
  const Status later = adapter.execute(2, 0, view, GridView::cell_index(g, swapped.data()));
  EXPECT_TRUE(later.ok()) << later.message;
}

// Particles with a NaN position are said on the first step that has them; the stats count
// them on every step.
TEST(Adapter, NonFiniteParticlesAreSaidOnceAndCountedEachStep) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {4, 4, 4}, 1.0);
  pts[5].x = std::numeric_limits<float>::quiet_NaN();
  test::LogCapture log;
  Adapter adapter(every(1));
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  for (std::int64_t step = 1; step <= 3; ++step) {
    ASSERT_TRUE(adapter.execute(step, 0, view).ok());
    EXPECT_EQ(adapter.last_stats().counts.dropped_nonfinite, 1u);
  }
  std::size_t told = 0;
  for (const std::string& w : log.at(LogLevel::warning))
    told += w.find("left out 1 particles with a NaN") != std::string::npos;
  EXPECT_EQ(told, 1u);
}

// A step executed twice is said once (its files would be written again, silently).
TEST(Adapter, AStepThatComesTwiceIsSaidOnce) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {4, 4, 4}, 1.0);
  test::LogCapture log;
  Adapter adapter(every(1));
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  for (const std::int64_t step : {1, 2, 2, 3, 3, 1})  // the last: a restart, not a repeat
    ASSERT_TRUE(adapter.execute(step, 0, view).ok());
  std::size_t told = 0;
  for (const std::string& w : log.at(LogLevel::warning))
    told += w.find("step 2 came twice") != std::string::npos;
  EXPECT_EQ(told, 1u);
  EXPECT_EQ(log.at(LogLevel::warning).size(), 1u);
}

// An adapter moved from answers as one with nothing to do, and says so; it never crashes the
// solver that calls it by mistake.
TEST(Adapter, AMovedFromAdapterRefusesToExecute) {
  QuietLog quiet;
  Adapter adapter(every(1));
  Adapter moved = std::move(adapter);
  const std::vector<Point> pts(8, Point{0, 0, 0});
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  EXPECT_FALSE(adapter.is_render_step(0, 0));  // NOLINT(bugprone-use-after-move): the point
  const Status s = adapter.execute_last(0, 0, view);
  EXPECT_EQ(s.code, StatusCode::invalid_input);
  EXPECT_EQ(s.message, "execute() on an adapter that was moved from");
  adapter.finish();
  EXPECT_TRUE(moved.execute(0, 0, view).ok());
}

// A spacing off by ten (other units; h for dx) is said once; the right one says nothing.
TEST(Adapter, ASpacingFarFromTheParticlesIsSaidOnce) {
  std::vector<Point> pts;
  test::add_lattice(pts, {0, 0, 0}, {16, 16, 16}, 0.01);
  const auto view = ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point));
  for (const double spacing : {0.001, 0.01, 0.1}) {
    test::LogCapture log;
    AdapterOptions o;
    o.classify.particle_spacing = spacing;
    Adapter adapter(o);
    for (std::int64_t step = 1; step <= 3; ++step) ASSERT_TRUE(adapter.execute(step, 0, view).ok());
    const std::vector<std::string> warnings = log.at(LogLevel::warning);
    if (spacing == 0.01) {
      EXPECT_TRUE(warnings.empty()) << log.all();
      continue;
    }
    ASSERT_EQ(warnings.size(), 1u) << spacing << ": " << log.all();
    EXPECT_NE(
        warnings[0].find(spacing < 0.01 ? "the spacing is too small" : "the spacing is too large"),
        std::string::npos)
        << warnings[0];
  }
}

TEST(Adapter, PipelineExceptionsAreCaught) {
  QuietLog quiet;
  std::vector<Point> pts(3, Point{1, 1, 1});
  Adapter adapter(every(1));
  auto recorder = std::make_shared<Recorder>();
  recorder->throw_on_process = true;
  adapter.set_pipeline(recorder);
  const Status s = adapter.execute(0, 0, ParticleView::aos(&pts[0].x, pts.size(), sizeof(Point)));
  EXPECT_EQ(s.code, StatusCode::pipeline_failed);
  EXPECT_EQ(s.message, "disk full");
}

TEST(Adapter, AttributesReachThePipeline) {
  std::vector<Point> pts(4, Point{1, 1, 1});
  std::vector<float> rho(4, 1000.f);
  AdapterOptions o = every(1);
  o.classify.attributes = {"density"};
  Adapter adapter(o);
  auto recorder = std::make_shared<Recorder>();
  adapter.set_pipeline(recorder);
  EXPECT_TRUE(
      adapter
          .execute(
              0, 0,
              ParticleView::aos(&pts[0].x, 4, sizeof(Point)).with_scalar("density", rho.data()))
          .ok());
  EXPECT_EQ(recorder->attribute_values, 4u);
}

TEST(Adapter, InvalidOptionsThrowAtConstruction) {
  auto message = [](AdapterOptions o) -> std::string {
    try {
      Adapter a(std::move(o));
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  AdapterOptions o;
  EXPECT_NE(message(o).find("particle_spacing"), std::string::npos);
  o = every(-1);
  EXPECT_NE(message(o).find("render_every = -1"), std::string::npos);
  o = every(1);
  o.classify.particle_spacing = std::nan("");
  EXPECT_NE(message(o).find("particle_spacing"), std::string::npos);
  o = every(1);
  o.classify.attributes = {"a", "a"};
  EXPECT_NE(message(o).find("'a' is listed twice"), std::string::npos);
  o = every(1);
  o.classify.full_count = 5;
  o.classify.particle_spacing = 0;
  EXPECT_EQ(message(o), "");
}

}  // namespace
}  // namespace voxspan
