// render/passes/compress.comp - compresses a tile's voxel columns into the span image (paper 001,
// sec. 3.1, 3.2, 4.3, 4.4), one thread per column, in two passes around a prefix sum:
//   count (default): scans the column (render/passes/column_scan.glsl); writes the pixel's
//     count (capped), total and inside length, the first u_scratch_spans spans and the last
//     exit to scratch, the stored count for the prefix sum, and capped-pixel stats.
//   COMPRESS_WRITE: with the scanned offsets, writes the pixel's offset and its spans: copied
//     from scratch when the stored list is known from it, else by scanning the column again.
// Reads: the tile's bits, the cell-state texture. Writes: see above.
// Cost: one read of the tile's bits (uvec4 loads, coalesced), a second only for columns with
// more than u_scratch_spans stored spans; two exp2 per run boundary.
layout(local_size_x = 64) in;

#include "render/perspective_grid.glsl"
#include "render/passes/bits.glsl"
#include "render/span_image.glsl"
#include "render/passes/column_scan.glsl"
#include "render/passes/depth_bounds.glsl"

layout(std430, binding = 2) readonly buffer Bits { uvec4 bits[]; };
layout(std430, binding = 3) buffer ScratchSpans { vec2 scratch_spans[]; };  // [k * pixels + p]
layout(std430, binding = 4) buffer ScratchCounts { uint scratch_counts[]; }; // count, then offset
layout(std430, binding = 5) buffer ScratchExits { float scratch_last_exit[]; };
layout(std430, binding = 6) buffer Stats { uint stats[]; };  // capped pixels, spans past caps
layout(std430, binding = 7) readonly buffer DepthBounds { uvec2 depth_bounds[]; };

uniform ivec4 u_tile;            // x0, y0, width, height
uniform uint u_cap;              // stored spans per pixel; 0 = no cap
uniform uint u_scratch_spans;    // spans per pixel the scratch holds
uniform uint u_span_base;        // COMPRESS_WRITE: this tile's first span in the image

uint g_pixel;        // tile pixel of this thread
uint g_image_pixel;  // its index in the span image
uint g_offset;       // COMPRESS_WRITE: its first span

uvec4 column_chunk(uint chunk) { return bits[chunk * u_tile_pixels + g_pixel]; }

// The chunks of the pixel's column that can hold fluid: its block's depth bounds, the large
// spheres', and from the near plane on when the ray starts inside inner-full cells. A layer of
// margin on each side absorbs float rounding between the bounds and the splat's chords.
bool column_chunks(ivec2 pixel, out uint first, out uint last) {
  uvec2 block = depth_bounds[depth_block(pixel)];
  uvec2 large = depth_bounds[u_depth_block_count];
  uvec2 b = max(block, large);
  bool near_full = inner_full_at(u_eye + u_near * world_ray(pixel));
  first = 0u;
  last = 0u;
  if (b.x == 0u && !near_full) return false;
  float nearest = (near_full || b.x == 0u) ? u_near : uintBitsToFloat(~b.x);
  float farthest = b.y == 0u ? u_grid_far : uintBitsToFloat(b.y);
  first = (max(layer_index(nearest), 1u) - 1u) >> 7u;
  last = min(layer_index(farthest) + 1u, u_layers - 1u) >> 7u;
  return true;
}

#ifndef COMPRESS_WRITE
float g_last_exit;

void on_span(uint index, float entry, float exit) {
  if (index < u_scratch_spans) scratch_spans[index * u_tile_pixels + g_pixel] = vec2(entry, exit);
  g_last_exit = exit;
}

void compress_pixel(ivec2 pixel) {
  g_last_exit = 0.0;
  float inside = 0.0;
  uint first, last;
  uint total = column_chunks(pixel, first, last) ? scan_column(pixel, first, last, inside) : 0u;
  uint count = u_cap == 0u ? total : min(total, u_cap);
  span_pixels[g_image_pixel].count = count;
  span_pixels[g_image_pixel].total = total;
  span_pixels[g_image_pixel].inside = inside;
  scratch_counts[g_pixel] = count;
  scratch_last_exit[g_pixel] = g_last_exit;
  if (count < total) {
    atomicAdd(stats[0], 1u);
    atomicAdd(stats[1], total - count);
  }
}
#else
// Sec. 3.1: past the cap, the last stored span grows to the last exit found.
void on_span(uint index, float entry, float exit) {
  if (u_cap == 0u || index < u_cap) span_depths[g_offset + index] = vec2(entry, exit);
  else span_depths[g_offset + u_cap - 1u].y = exit;
}

void compress_pixel(ivec2 pixel) {
  g_offset = u_span_base + scratch_counts[g_pixel];
  span_pixels[g_image_pixel].offset = g_offset;
  uint count = span_pixels[g_image_pixel].count;
  if (count == 0u) return;
  if (count <= u_scratch_spans) {
    for (uint k = 0u; k < count; ++k)
      span_depths[g_offset + k] = scratch_spans[k * u_tile_pixels + g_pixel];
    if (count < span_pixels[g_image_pixel].total)
      span_depths[g_offset + count - 1u].y = scratch_last_exit[g_pixel];
  } else {
    float inside;
    uint first, last;
    column_chunks(pixel, first, last);
    scan_column(pixel, first, last, inside);
  }
}
#endif

void main() {
  for (uint p = gl_GlobalInvocationID.x; p < u_tile_pixels; p += gl_NumWorkGroups.x * 64u) {
    g_pixel = p;
    ivec2 pixel = u_tile.xy + ivec2(p % uint(u_tile.z), p / uint(u_tile.z));
    g_image_pixel = uint(pixel.x) + uint(pixel.y) * uint(u_image.x);
    compress_pixel(pixel);
  }
}
