#include "render/gl/passes/depth_bounds.h"

#include <algorithm>
#include <bit>
#include <cmath>

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

std::vector<std::uint32_t> inner_full_depth_bounds(const PerspectiveGrid& grid,
                                                   const CellStatesView& cells) {
  std::vector<std::uint32_t> bounds(2 * (depth_block_count(grid) + 1), 0);
  if (cells.empty() || grid.empty()) return bounds;
  const double radius = 0.5 * std::sqrt(3.0) * cells.cell_size;
  const int across = blocks_across(grid);
  for (int k = 0; k < cells.dims[2]; ++k)
    for (int j = 0; j < cells.dims[1]; ++j)
      for (int i = 0; i < cells.dims[0]; ++i) {
        const std::size_t c =
            std::size_t(i) +
            std::size_t(cells.dims[0]) * (std::size_t(j) + std::size_t(cells.dims[1]) * k);
        if (cells.states[c] != cell::kInnerFull) continue;
        const glm::dvec3 centre(cells.origin[0] + (i + 0.5) * cells.cell_size,
                                cells.origin[1] + (j + 0.5) * cells.cell_size,
                                cells.origin[2] + (k + 0.5) * cells.cell_size);
        const glm::dvec3 v = grid.view().to_view(centre);
        const PixelRect r = grid.sphere_pixels(v, radius);
        if (r.empty()) continue;
        // The binning pass's encoding: both kept as maxima, the nearest depth inverted.
        const float nearest = float(std::max(v.z - radius, grid.near()));
        const float farthest = float(std::min(v.z + radius, grid.grid_far()));
        if (!(nearest <= farthest)) continue;
        const std::uint32_t near_bits = ~std::bit_cast<std::uint32_t>(nearest);
        const std::uint32_t far_bits = std::bit_cast<std::uint32_t>(farthest);
        for (int by = r.y0 / kDepthBlock; by <= r.y1 / kDepthBlock; ++by)
          for (int bx = r.x0 / kDepthBlock; bx <= r.x1 / kDepthBlock; ++bx) {
            const std::size_t b = 2 * (std::size_t(bx) + std::size_t(by) * std::size_t(across));
            bounds[b] = std::max(bounds[b], near_bits);
            bounds[b + 1] = std::max(bounds[b + 1], far_bits);
          }
      }
  return bounds;
}

}  // namespace voxspan
