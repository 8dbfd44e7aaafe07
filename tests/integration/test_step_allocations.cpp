// Once sizes are stable, a render step allocates nothing new on the solver's thread: the
// renderer reuses its GPU buffers, the read-back images and the snapshots' copies live in
// pooled slots, the stats record keeps its names, the writer's queue is a ring, the live page's
// mailbox keeps its pictures' and passes' storage. Counted with
// a replaced operator new, on the solver's thread only (the writer's thread encodes PNGs and
// builds VDB grids, which allocate as libpng and OpenVDB do).
#include <gtest/gtest.h>

#include "dambreak_run.h"
#include "tests/support/allocation_counter.h"
#include "tests/support/temp_folder.h"
#include "voxspan/adapter.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

// Render steps on `backend` ("cpu", or "gl, readback: later": its pictures read back later).
void expect_render_steps_allocate_nothing(const std::string& backend) {
  test::TempFolder dir;
  // A particle spacing of its own, and a tank that does not move: the same sizes every step.
  dambreak::DamBreak sim(test::small_dambreak(3000));
  const std::string yaml =
      "output_folder: " + dir.path().string() + "\nrenderer: {backend: " + backend + "}" + R"(
trigger: {every_steps: 1}
views:
  - {name: a, width: 96, height: 64}
  - {name: b, width: 80, height: 80, shading: refractive, camera: {direction: [1, 1, -0.5], framing: first}}
outputs:
  vdb: {enabled: true, trigger: {every_steps: 4}, attributes: [velocity, density]}
  vtk: {enabled: true, trigger: {every_steps: 4}, attributes: [velocity]}
  depth: {enabled: true, trigger: {every_steps: 2}}
writer: {queue_size: 64, fsync: false}
live: {enabled: true}
)";
  Adapter adapter = adapter_from_config_text(yaml, test::solver_options(sim), "alloc.yaml");
  const dambreak::Fluid& f = sim.fluid();
  const dambreak::GridShape& g = sim.fluid_grid().shape();
  auto execute = [&](std::int64_t step) {
    const auto particles = ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size())
                               .with_vector("velocity", f.vx.data(), f.vy.data(), f.vz.data())
                               .with_scalar("density", f.rho.data());
    const auto grid = GridView::offsets(GridGeometry{g.origin, g.cell_size, g.dims},
                                        sim.fluid_grid().offsets().data());
    return adapter.execute(step, 1e-4 * double(step), particles, grid);
  };
  // The same particles every step (the solver does not move): warm-up steps size everything.
  // The writer is waited for after each step, so that each pool needs the same slots in both
  // phases whatever the machine's load (a writer that lags takes more slots, up to the
  // queue's size + 2 per kind, each made once: slot_pool.h).
  for (std::int64_t step = 1; step <= 16; ++step) {
    ASSERT_TRUE(execute(step).ok());
    adapter.finish();
  }
  // One window of 8 steps (2 with snapshots); where one allocates, its backtrace says where.
  test::trace_thread_allocations(4);
  const long before = test::thread_allocations();
  for (std::int64_t step = 17; step < 25; ++step) {
    ASSERT_TRUE(execute(step).ok());
    adapter.finish();
  }
  const long allocated = test::thread_allocations() - before;
  test::trace_thread_allocations(0);
  EXPECT_EQ(allocated, 0) << "allocations in 8 render steps (their backtraces above)";
}

TEST(StepAllocations, RenderStepsWithFramesStatsAndSnapshotsAllocateNothingOnceStable) {
  expect_render_steps_allocate_nothing("cpu");
}

TEST(StepAllocations, SoDoTheGlRenderersWithTheirPicturesReadBackLater) {
  expect_render_steps_allocate_nothing("gl, readback: later");
}

// Conditions checked on every step, rendering on some and not on others: the reductions, the
// expressions and the edges allocate nothing either.
TEST(StepAllocations, StepsWithConditionsAllocateNothingOnceStable) {
  test::TempFolder dir;
  dambreak::DamBreak sim(test::small_dambreak(3000));
  const std::string yaml = "output_folder: " + dir.path().string() + R"(
constants: {fast: 1e9}
boxes: {low: [[-.inf, -.inf, -.inf], [.inf, .inf, 0.1]]}
trigger: {every_steps: 2, when: "max(velocity) > fast or count(low) < 0"}
views: [{name: a, width: 64, height: 48}]
outputs:
  stats: {trigger: {when: "mean(density, low) > 0 and sin(step) > 0", cooldown_steps: 2}}
writer: {queue_size: 64, fsync: false}
)";
  Adapter adapter = adapter_from_config_text(yaml, test::solver_options(sim), "alloc.yaml");
  const dambreak::Fluid& f = sim.fluid();
  auto execute = [&](std::int64_t step) {
    const auto particles = ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size())
                               .with_vector("velocity", f.vx.data(), f.vy.data(), f.vz.data())
                               .with_scalar("density", f.rho.data());
    return adapter.execute(step, 1e-4 * double(step), particles);
  };
  for (std::int64_t step = 1; step <= 16; ++step) {
    ASSERT_TRUE(execute(step).ok());
    adapter.finish();
  }
  const std::int64_t renders_before = adapter.render_steps();
  test::trace_thread_allocations(4);
  const long before = test::thread_allocations();
  for (std::int64_t step = 17; step < 33; ++step) {
    ASSERT_TRUE(execute(step).ok());
    adapter.finish();
  }
  const long allocated = test::thread_allocations() - before;
  test::trace_thread_allocations(0);
  EXPECT_EQ(allocated, 0) << "allocations in 16 steps with conditions (their backtraces above)";
  // Every other step renders, and the stats' condition rises at 19, 26 and 32 (sin(step) > 0
  // again): one more step with work.
  EXPECT_EQ(adapter.render_steps() - renders_before, 9);
}

}  // namespace
}  // namespace voxspan
