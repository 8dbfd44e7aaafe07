#include "render/passes/depth_bounds.h"

namespace voxspan {
namespace {
int blocks_across(const PerspectiveGrid& grid) {
  return (grid.width() + kDepthBlock - 1) / kDepthBlock;
}
int blocks_down(const PerspectiveGrid& grid) {
  return (grid.height() + kDepthBlock - 1) / kDepthBlock;
}
}  // namespace

std::size_t depth_block_count(const PerspectiveGrid& grid) {
  return static_cast<std::size_t>(blocks_across(grid)) *
         static_cast<std::size_t>(blocks_down(grid));
}

void set_depth_block_uniforms(const gl::Program& program, const PerspectiveGrid& grid) {
  program.set("u_depth_blocks_x", blocks_across(grid));
  program.set("u_depth_block_count", static_cast<int>(depth_block_count(grid)));
}

}  // namespace voxspan
