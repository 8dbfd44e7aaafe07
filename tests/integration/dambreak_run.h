// The dam break of examples/dambreak with an adapter in its loop, as the example program runs
// it (fluid SoA arrays and the solver's compact grid as views, velocity and density attached),
// at test size (tests only).
#pragma once

#include <cstdint>
#include <string>

#include "sph.h"
#include "voxspan/adapter.h"

namespace voxspan::test {

// A small 3D dam break: a few thousand particles, so that a step takes milliseconds.
inline dambreak::Config small_dambreak(std::size_t particles = 4000) {
  dambreak::Config c;
  c.particles = particles;
  return c;
}

// The options a solver passes: its rest spacing.
inline AdapterOptions solver_options(const dambreak::DamBreak& sim) {
  AdapterOptions o;
  o.classify.particle_spacing = sim.dx();
  return o;
}

struct RunResult {
  std::int64_t steps = 0;   // solver steps done (all of them, whatever the adapter said)
  std::int64_t failed = 0;  // execute() calls that returned an error status
  std::string first_failure;
};

// Runs `steps` solver steps, calling the adapter after each (execute_last on the last one),
// then finish().
inline RunResult run_dambreak(dambreak::DamBreak& sim, Adapter& adapter, std::int64_t steps) {
  RunResult r;
  for (std::int64_t step = 1; step <= steps; ++step) {
    sim.step();
    const dambreak::Fluid& f = sim.fluid();
    const auto particles = ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size())
                               .with_vector("velocity", f.vx.data(), f.vy.data(), f.vz.data())
                               .with_scalar("density", f.rho.data());
    const dambreak::GridShape& g = sim.fluid_grid().shape();
    const auto grid = GridView::offsets(GridGeometry{g.origin, g.cell_size, g.dims},
                                        sim.fluid_grid().offsets().data());
    const Status s = step == steps ? adapter.execute_last(step, sim.time(), particles, grid)
                                   : adapter.execute(step, sim.time(), particles, grid);
    if (!s.ok() && r.failed++ == 0) r.first_failure = s.message;
    ++r.steps;
  }
  adapter.finish();
  return r;
}

}  // namespace voxspan::test
