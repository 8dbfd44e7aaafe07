// render/passes/depth_bounds.h - the C++ side of render/passes/depth_bounds.glsl: how many
// 16x16-pixel blocks the image has and the uniforms that say so. BinPass fills the bounds,
// CompressPass reads them.
#pragma once

#include <cstddef>

#include "render/gl/objects.h"
#include "render/perspective_grid.h"

namespace voxspan {

constexpr int kDepthBlock = 16;

// Blocks in the image (the buffer holds one more entry, for the large spheres).
std::size_t depth_block_count(const PerspectiveGrid& grid);
void set_depth_block_uniforms(const gl::Program& program, const PerspectiveGrid& grid);

}  // namespace voxspan
