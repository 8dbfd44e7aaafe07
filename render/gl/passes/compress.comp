// render/gl/passes/compress.comp - compresses a tile's voxel columns into the span image ([ZD15],
// sec. 3.1, 3.2, 4.3, 4.4), one thread per column, in passes around a prefix sum:
//   count (default): scans the column (render/gl/passes/column_scan.glsl) over the depth range
//     its block's spheres cover; writes the pixel's count (capped), total and inside length,
//     the first u_scratch_spans spans and the last exit to scratch, the stored count for the
//     prefix sum, capped-pixel stats, and lists the pixels whose stored spans do not fit the
//     scratch;
//   COMPRESS_COPY: with the scanned offsets, writes each pixel's offset and copies its spans
//     from scratch (extending the last one past a cap);
//   COMPRESS_RESCAN: scans the listed pixels' columns again, writing their spans directly.
// Keeping the re-scan out of the copy pass matters on llvmpipe, which runs both sides of a
// branch under a mask.
// Reads: the tile's bits, the cell-state texture, the depth bounds. Writes: see above.
// Cost: one coalesced read of the chunks of the tile's bits that can hold fluid (a second
// only for listed columns); two exp2 per run boundary.
layout(local_size_x = 64) in;

#include "render/gl/perspective_grid.glsl"
#include "render/gl/passes/bits.glsl"
#include "render/gl/span_image.glsl"
#include "render/gl/passes/column_scan.glsl"
#include "render/gl/passes/column_range.glsl"

layout(std430, binding = BITS_BINDING) readonly buffer Bits { uvec4 bits[]; };
layout(std430, binding = SCRATCH_SPANS_BINDING) buffer ScratchSpans {
  vec2 scratch_spans[];  // [k * pixels + p]
};
layout(std430, binding = SCRATCH_COUNTS_BINDING) buffer ScratchCounts {
  uint scratch_counts[];  // count, then offset
};
layout(std430, binding = SCRATCH_EXITS_BINDING) buffer ScratchExits { float scratch_last_exit[]; };
layout(std430, binding = STATS_BINDING) buffer Stats {
  uint stats[];  // capped pixels, spans past caps
};
layout(std430, binding = RESCAN_BINDING) buffer Rescan {
  uint rescan[];  // count, then tile pixels
};

uniform uint u_cap;              // stored spans per pixel; 0 = no cap
uniform uint u_scratch_spans;    // spans per pixel the scratch holds
uniform uint u_span_base;        // copy, rescan: this tile's first span in the image
uniform uint u_rescan_count;     // rescan: pixels listed

uint g_pixel = 0u;        // tile pixel of this thread (set first thing in main; initialized
                          // so that Mesa does not warn of a read before it)
uint g_image_pixel = 0u;  // its index in the span image
uint g_offset = 0u;       // copy, rescan: its first span

uvec4 column_chunk(uint chunk) { return bits[chunk * u_tile_pixels + g_pixel]; }

#if !defined(COMPRESS_COPY) && !defined(COMPRESS_RESCAN)
float g_last_exit = 0.0;

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
  if (count > u_scratch_spans) rescan[1u + atomicAdd(rescan[0], 1u)] = g_pixel;
}
#elif defined(COMPRESS_COPY)
void on_span(uint index, float entry, float exit) {}

void compress_pixel(ivec2 pixel) {
  g_offset = u_span_base + scratch_counts[g_pixel];
  span_pixels[g_image_pixel].offset = g_offset;
  uint count = span_pixels[g_image_pixel].count;
  if (count == 0u || count > u_scratch_spans) return;
  for (uint k = 0u; k < count; ++k)
    span_depths[g_offset + k] = scratch_spans[k * u_tile_pixels + g_pixel];
  // Sec. 3.1: past the cap, the last stored span grows to the last exit found.
  if (count < span_pixels[g_image_pixel].total)
    span_depths[g_offset + count - 1u].y = scratch_last_exit[g_pixel];
}
#else
// Sec. 3.1: past the cap, the last stored span grows to the last exit found.
void on_span(uint index, float entry, float exit) {
  if (u_cap == 0u || index < u_cap) span_depths[g_offset + index] = vec2(entry, exit);
  else span_depths[g_offset + u_cap - 1u].y = exit;
}

void compress_pixel(ivec2 pixel) {
  g_offset = u_span_base + scratch_counts[g_pixel];
  float inside;
  uint first, last;
  column_chunks(pixel, first, last);
  scan_column(pixel, first, last, inside);
}
#endif

void run_pixel(uint p) {
  g_pixel = p;
  ivec2 pixel = tile_image_pixel(p);
  g_image_pixel = uint(pixel.x) + uint(pixel.y) * uint(u_image.x);
  compress_pixel(pixel);
}

void main() {
  uint stride = gl_NumWorkGroups.x * 64u;
#ifdef COMPRESS_RESCAN
  for (uint i = gl_GlobalInvocationID.x; i < u_rescan_count; i += stride) run_pixel(rescan[1u + i]);
#else
  for (uint p = gl_GlobalInvocationID.x; p < u_tile_pixels; p += stride) run_pixel(p);
#endif
}
