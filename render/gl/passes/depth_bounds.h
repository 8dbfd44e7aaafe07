// render/gl/passes/depth_bounds.h - the C++ side of render/gl/passes/depth_bounds.glsl: how many
// 16x16-pixel blocks the image has and the uniforms that say so. BinPass fills the bounds,
// CompressPass reads them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/gl/objects.h"
#include "render/perspective_grid.h"
#include "voxspan/cell_states.h"

namespace voxspan {

constexpr int kDepthBlock = 16;

// Blocks in the image (the buffer holds one more entry, for the large spheres).
std::size_t depth_block_count(const PerspectiveGrid& grid);
void set_depth_block_uniforms(const gl::Program& program, const PerspectiveGrid& grid);

// The depth bounds the inner-full cells of `cells` need (each cell's bounding sphere, as the
// binning pass takes a particle's), in the buffer's layout (depth_block_count + 1 entries of
// two words: ~bits(nearest), bits(farthest); zero where no cell reaches). For a process that
// voxelizes part of the fluid (an MPI rank), whose inner-full cells may end where another
// rank's particles begin rather than at its own boundary particles.
std::vector<std::uint32_t> inner_full_depth_bounds(const PerspectiveGrid& grid,
                                                   const CellStatesView& cells);

}  // namespace voxspan
