// The voxelization issue's accuracy scenes (tests/render/gl/test_voxelize_accuracy.cpp: one
// sphere, a lattice block, the dam break, 24 stacked layers, a 3D checkerboard, a random cloud
// with mixed radii) with their cameras and voxelization options, for measuring how close the
// shaded pictures come to the exact reference's.
#pragma once

#include <string>
#include <vector>

#include "render/gl/voxelizer.h"
#include "render/shade_options.h"
#include "tools/scenes/scenes.h"

namespace voxspan::test {

struct AccuracyScene {
  std::string name;
  Particles particles;
  Camera camera;
  VoxelizeOptions options;  // gap bridging, span cap; the grid's alpha is the caller's
  double ground_tile = 0.1;
};

// Images of width x height (the cameras keep their framing at any size).
std::vector<AccuracyScene> accuracy_scenes(int width, int height);

// Shading options for the tests and the accuracy figures of bench_shading: a fluid that absorbs
// enough to show its depth (a few world units of it go dark), ground tiles of `tile`.
ShadeOptions test_shading(ShadeMode mode, double tile = 0.1);

}  // namespace voxspan::test
