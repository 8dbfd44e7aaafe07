// tests/support/tank.h - a closed tank of wall particles (Adapter::set_scenery) around the
// lattice block of view_tests.h: three layers of the block's lattice on every side, lid
// included, so that only the cutaway shows the water.
#pragma once

#include <vector>

#include "voxspan/particles.h"

namespace voxspan::test {

struct Tank {
  std::vector<double> xyz;  // x, y, z per particle
  // Around a block of nx x ny x nz lattice sites of `spacing` from the origin.
  Tank(double spacing, int nx = 20, int ny = 10, int nz = 10, int layers = 3) {
    for (int k = -layers; k < nz + layers; ++k)
      for (int j = -layers; j < ny + layers; ++j)
        for (int i = -layers; i < nx + layers; ++i) {
          if (i >= 0 && i < nx && j >= 0 && j < ny && k >= 0 && k < nz) continue;
          for (int a : {i, j, k}) xyz.push_back((a + 0.5) * spacing);
        }
  }
  std::size_t size() const { return xyz.size() / 3; }
  // Particles [first, last) of the tank.
  ParticleView view(std::size_t first = 0, std::size_t last = std::size_t(-1)) const {
    last = std::min(last, size());
    return ParticleView::aos(xyz.data() + 3 * first, last > first ? last - first : 0);
  }
};

}  // namespace voxspan::test
