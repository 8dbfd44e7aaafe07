// render/gl/passes/bits.glsl - the layout of a tile's voxel bits and bit-range masks, shared by the
// splat (writer), the column clear and the compress pass (reader).
//
// Layout: a column holds u_chunks uvec4 chunks (128 layers each); chunk c of tile pixel p is
// uvec4 number c * u_tile_pixels + p, so neighbouring columns' chunks are neighbours in memory
// and the one-thread-per-column compress reads coalesced (GPU-NOTES: uvec4 loads, 680-890
// GB/s on an H100). Bit b of 32-bit word w of a column is layer 32 w + b. The uniforms are set
// by set_bit_uniforms() (render/gl/passes/bits.h).

uniform uint u_chunks;       // uvec4 chunks per column: ceil(L / 128)
uniform uint u_tile_pixels;  // pixels in this tile
uniform ivec4 u_tile;        // x0, y0, width, height

// The image pixel of tile pixel p (row by row through the tile).
ivec2 tile_image_pixel(uint p) { return u_tile.xy + ivec2(p % uint(u_tile.z), p / uint(u_tile.z)); }

// Index, in 32-bit words, of word w of tile pixel p.
uint bit_word_index(uint p, uint w) { return ((w >> 2u) * u_tile_pixels + p) * 4u + (w & 3u); }

// Bits lo..hi (inclusive, 0 <= lo <= hi <= 31) of a word.
uint bit_range_mask(uint lo, uint hi) {
  uint upper = hi == 31u ? 0xFFFFFFFFu : ((1u << (hi + 1u)) - 1u);
  return upper & ~((1u << lo) - 1u);
}
