// The voxelization tests share tests/render/gl's one-context fixture (context(), shaders()) and one
// voxelizer (program compiles are slow on llvmpipe; the passes leave no state behind for the
// next test anyway), and voxelize-and-download in one call.
#pragma once

#include <span>

#include "render/frame_stats.h"
#include "render/gl/voxelizer.h"
#include "render/span_image.h"
#include "tests/render/gl/gl_fixture.h"

namespace voxspan::test {

Voxelizer& voxelizer();

// Runs the GPU voxelization and reads the span image back; `stats` gets its counts and times.
SpanImage voxelize(const Camera& camera, std::span<const ParticleSphere> particles,
                   const VoxelizeOptions& options, const CellStatesView& cells = {},
                   FrameStats* stats = nullptr);

}  // namespace voxspan::test
