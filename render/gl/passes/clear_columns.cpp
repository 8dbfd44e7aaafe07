#include "render/gl/passes/clear_columns.h"

#include "render/gl/bindings.h"
#include "render/gl/passes/bits.h"
#include "render/gl/passes/depth_bounds.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {
enum Binding : GLuint { kBits, kDepthBounds };
}  // namespace

ClearColumnsPass::ClearColumnsPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute(
          "render/gl/passes/clear_columns.comp",
          binding::cell_state_defines() +
              gl::defines({{"BITS_BINDING", kBits}, {"DEPTH_BOUNDS_BINDING", kDepthBounds}}))) {}

void ClearColumnsPass::run(const gl::Buffer& bits, const gl::Buffer& depth_bounds,
                           const PerspectiveGrid& grid, const TileLayout& layout,
                           const TileRect& tile, const CellStateTexture& cells) const {
  const auto pixels = static_cast<std::size_t>(tile.pixels());
  set_grid_uniforms(program_, grid);
  set_depth_block_uniforms(program_, grid);
  cells.bind(program_);
  set_bit_uniforms(program_, layout, tile);
  bits.bind_range(GL_SHADER_STORAGE_BUFFER, kBits, 0, layout.column_bytes * pixels);
  depth_bounds.bind(GL_SHADER_STORAGE_BUFFER, kDepthBounds);
  dispatch_strided(program_, pixels);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace voxspan
