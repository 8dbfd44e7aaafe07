// render/gl/passes/clear_columns.h - zeroes the chunks of a tile's columns that can hold fluid
// (render/gl/passes/clear_columns.comp), instead of the whole tile: most of the perspective grid
// is empty depth that neither the splat writes nor the compress pass reads.
// Reads: BinPass::depth_bounds(), the cell states. Writes: the tile's bits.
// Cost: one 16-byte store per chunk in range.
#pragma once

#include "render/gl/cell_state_texture.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"
#include "render/gl/tiling.h"
#include "render/perspective_grid.h"

namespace voxspan {

class ClearColumnsPass {
 public:
  explicit ClearColumnsPass(const gl::ShaderLibrary& shaders);
  void run(const gl::Buffer& bits, const gl::Buffer& depth_bounds, const PerspectiveGrid& grid,
           const TileLayout& layout, const TileRect& tile, const CellStateTexture& cells) const;

 private:
  gl::Program program_;
};

}  // namespace voxspan
