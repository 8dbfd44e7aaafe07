// render/gl/passes/clear_columns.comp - zeroes, in each column of a tile, the chunks that can hold
// fluid (render/gl/passes/column_range.glsl) and nothing else: the splat writes and the compress
// pass reads only those, so clearing the empty depth of the grid would be wasted bandwidth
// ([ZD15] sec. 3.1: the tile's grid is cleared before it is splatted).
// Reads: the depth bounds, the cell states at the near plane. Writes: the tile's bits.
// Cost: one uvec4 store per chunk in range, coalesced across neighbouring columns.
layout(local_size_x = 64) in;

#include "render/gl/perspective_grid.glsl"
#include "render/gl/passes/bits.glsl"
#include "render/gl/passes/cell_march.glsl"
#include "render/gl/passes/column_range.glsl"

layout(std430, binding = BITS_BINDING) writeonly buffer Bits { uvec4 bits[]; };

void main() {
  for (uint p = gl_GlobalInvocationID.x; p < u_tile_pixels; p += gl_NumWorkGroups.x * 64u) {
    ivec2 pixel = tile_image_pixel(p);
    uint first, last;
    if (!column_chunks(pixel, first, last)) continue;
    for (uint c = first; c <= last; ++c) bits[c * u_tile_pixels + p] = uvec4(0u);
  }
}
