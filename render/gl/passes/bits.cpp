#include "render/gl/passes/bits.h"

namespace voxspan {

void set_bit_uniforms(const gl::Program& program, const TileLayout& layout, const TileRect& tile) {
  program.set("u_chunks", static_cast<unsigned>(layout.column_bytes / 16));
  program.set("u_tile_pixels", static_cast<unsigned>(tile.pixels()));
  program.set("u_tile", glm::ivec4(tile.x0, tile.y0, tile.width, tile.height));
}

}  // namespace voxspan
