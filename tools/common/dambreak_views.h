// tools/common/dambreak_views.h - the examples' dam-break solver (examples/dambreak/sph.h) as the
// adapter sees it, for the tools that run it in their own loop: its fluid particles (with their
// velocity and density) and its neighbour-search grid, as zero-copy views.
#pragma once

#include "sph.h"
#include "voxspan/adapter.h"

namespace voxspan::tools {

inline ParticleView fluid_view(const dambreak::Fluid& f) {
  return ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size())
      .with_vector("velocity", f.vx.data(), f.vy.data(), f.vz.data())
      .with_scalar("density", f.rho.data());
}

inline GridView fluid_grid(const dambreak::DamBreak& sim) {
  const dambreak::GridShape& g = sim.fluid_grid().shape();
  return GridView::offsets(GridGeometry{g.origin, g.cell_size, g.dims},
                           sim.fluid_grid().offsets().data());
}

}  // namespace voxspan::tools
