// render/gl/passes/bin.comp - sorts particles into the screen tiles their spheres touch, once per
// frame, so that each tile splats only its own particles (the paper re-splats all of them for
// every tile, sec. 3.1). A small sphere touching several tiles goes into each; large spheres
// (render/gl/passes/sphere_work.glsl) go to one list of their own, splatted by splat_large.comp.
//   count (default): tile_counts[t] += small spheres touching tile t; large[0] += large spheres;
//     the depth bounds of the screen blocks they touch grow (render/gl/passes/depth_bounds.glsl);
//   BIN_SCATTER: with tile_counts[t] = the first slot of tile t (the exclusive prefix sum of the
//     counts), writes each small sphere's index into the slots of its tiles and each large
//     sphere's into the large list (order within a list is arbitrary: atomic OR does not care);
//   BIN_LARGE_ONLY: only the large spheres (count, or with BIN_SCATTER the list), for the
//     paper's re-splat-everything mode.
// Reads: particles (vec4). Writes: tile counts or cursors, tile lists, the large list.
// Cost: one footprint per particle; atomics on a shared-memory tally per work group, one global
// atomic per (work group, tile) (BIN_SHARED_TILES tiles at most; beyond, global atomics).
layout(local_size_x = 256) in;

#include "render/gl/perspective_grid.glsl"
#include "render/gl/passes/sphere_work.glsl"
#include "render/gl/passes/depth_bounds.glsl"

layout(std430, binding = PARTICLES_BINDING) readonly buffer Particles { vec4 particles[]; };
layout(std430, binding = TILE_COUNTS_BINDING) buffer TileCounts { uint tile_counts[]; };
layout(std430, binding = TILE_LISTS_BINDING) writeonly buffer TileLists { uint tile_lists[]; };
layout(std430, binding = LARGE_BINDING) buffer Large {
  uint large[];  // count, cursor
};
layout(std430, binding = LARGE_LIST_BINDING) writeonly buffer LargeList { uint large_list[]; };
layout(std430, binding = DEPTH_BOUNDS_BINDING) buffer DepthBounds { uvec2 depth_bounds[]; };

uniform uint u_count;       // particles
uniform ivec2 u_tile_size;  // largest tile, pixels
uniform ivec2 u_tiles;      // tiles across, down

// Sorts sphere i: false when culled; else large, or small with the tiles (tx0, ty0, tx1, ty1
// inclusive) it touches. The count pass also grows the depth bounds it touches.
bool sphere_tiles(uint i, out bool is_large, out ivec4 tiles) {
  is_large = false;
  tiles = ivec4(0, 0, -1, -1);
  if (i >= u_count) return false;
  vec4 sphere;
  if (!view_sphere(particles[i], sphere)) return false;
  ivec4 r = sphere_pixels(sphere.xyz, sphere.w);
  if (r.x > r.z || r.y > r.w) return false;
  is_large = sphere_is_large(sphere, r);
  tiles = ivec4(r.xy / u_tile_size, r.zw / u_tile_size);
#ifndef BIN_SCATTER
  uvec2 bounds =
      depth_bounds_bits(max(sphere.z - sphere.w, u_near), min(sphere.z + sphere.w, u_grid_far));
  ivec4 blocks = is_large ? ivec4(0, 0, -1, -1) : r / kDepthBlock;
  if (is_large) {
    atomicMax(depth_bounds[u_depth_block_count].x, bounds.x);
    atomicMax(depth_bounds[u_depth_block_count].y, bounds.y);
  }
  for (int by = blocks.y; by <= blocks.w; ++by)
    for (int bx = blocks.x; bx <= blocks.z; ++bx) {
      int b = bx + by * u_depth_blocks_x;
      atomicMax(depth_bounds[b].x, bounds.x);
      atomicMax(depth_bounds[b].y, bounds.y);
    }
#endif
  return true;
}

void add_large(uint i) {
#ifndef BIN_SCATTER
  atomicAdd(large[0], 1u);
#else
  large_list[atomicAdd(large[1], 1u)] = i;
#endif
}

#if defined(BIN_SHARED_TILES) && !defined(BIN_LARGE_ONLY)
shared uint s_tally[BIN_SHARED_TILES];
#ifdef BIN_SCATTER
shared uint s_base[BIN_SHARED_TILES];
#endif

void main() {
  uint tile_count = uint(u_tiles.x * u_tiles.y);
  uint lane = gl_LocalInvocationID.x;
  uint batches = (u_count + 255u) / 256u;
  for (uint batch = gl_WorkGroupID.x; batch < batches; batch += gl_NumWorkGroups.x) {
    for (uint t = lane; t < tile_count; t += 256u) s_tally[t] = 0u;
    barrier();
    uint i = batch * 256u + lane;
    bool is_large;
    ivec4 tiles;
    bool small = sphere_tiles(i, is_large, tiles) && !is_large;
    if (is_large) add_large(i);
    if (small)
      for (int ty = tiles.y; ty <= tiles.w; ++ty)
        for (int tx = tiles.x; tx <= tiles.z; ++tx) atomicAdd(s_tally[tx + ty * u_tiles.x], 1u);
    barrier();
#ifndef BIN_SCATTER
    for (uint t = lane; t < tile_count; t += 256u)
      if (s_tally[t] != 0u) atomicAdd(tile_counts[t], s_tally[t]);
#else
    for (uint t = lane; t < tile_count; t += 256u) {
      if (s_tally[t] != 0u) s_base[t] = atomicAdd(tile_counts[t], s_tally[t]);
      s_tally[t] = 0u;
    }
    barrier();
    if (small)
      for (int ty = tiles.y; ty <= tiles.w; ++ty)
        for (int tx = tiles.x; tx <= tiles.z; ++tx) {
          uint t = uint(tx + ty * u_tiles.x);
          tile_lists[s_base[t] + atomicAdd(s_tally[t], 1u)] = i;
        }
#endif
    barrier();
  }
}
#else
void main() {
  for (uint i = gl_GlobalInvocationID.x; i < u_count; i += gl_NumWorkGroups.x * 256u) {
    bool is_large;
    ivec4 tiles;
    if (!sphere_tiles(i, is_large, tiles)) continue;
    if (is_large) {
      add_large(i);
      continue;
    }
#ifndef BIN_LARGE_ONLY
    for (int ty = tiles.y; ty <= tiles.w; ++ty)
      for (int tx = tiles.x; tx <= tiles.z; ++tx) {
#ifndef BIN_SCATTER
        atomicAdd(tile_counts[tx + ty * u_tiles.x], 1u);
#else
        tile_lists[atomicAdd(tile_counts[tx + ty * u_tiles.x], 1u)] = i;
#endif
      }
#endif
  }
}
#endif
