// render/passes/bin.comp - sorts particles into the screen tiles their spheres touch, once per
// frame, so that each tile splats only its own particles (the paper re-splats all of them for
// every tile, sec. 3.1). A sphere touching several tiles goes into each.
//   count (default): tile_counts[t] += spheres touching tile t;
//   BIN_SCATTER: with tile_counts[t] = the first slot of tile t (the exclusive prefix sum of the
//     counts), writes each sphere's index into the slots of its tiles (order within a tile is
//     arbitrary: the splat's atomic OR does not care).
// Reads: particles (vec4). Writes: tile counts or cursors, tile lists.
// Cost: one footprint per particle; atomics on a shared-memory tally per work group, one global
// atomic per (work group, tile) (BIN_SHARED_TILES tiles at most; beyond, global atomics).
layout(local_size_x = 256) in;

#include "render/perspective_grid.glsl"

layout(std430, binding = 0) readonly buffer Particles { vec4 particles[]; };
layout(std430, binding = 1) buffer TileCounts { uint tile_counts[]; };
#ifdef BIN_SCATTER
layout(std430, binding = 2) writeonly buffer TileLists { uint tile_lists[]; };
#endif

uniform uint u_count;       // particles
uniform ivec2 u_tile_size;  // largest tile, pixels
uniform ivec2 u_tiles;      // tiles across, down

// The tiles (tx0, ty0, tx1, ty1 inclusive) the sphere touches; false when it is culled.
bool sphere_tiles(uint i, out ivec4 tiles) {
  tiles = ivec4(0, 0, -1, -1);
  if (i >= u_count) return false;
  vec4 p = particles[i];
  if (!valid_sphere(p)) return false;
  vec3 c = to_view(p.xyz);
  if (c.z + p.w <= u_near) return false;
  ivec4 r = sphere_pixels(c, p.w);
  if (r.x > r.z || r.y > r.w) return false;
  tiles = ivec4(r.xy / u_tile_size, r.zw / u_tile_size);
  return true;
}

#ifdef BIN_SHARED_TILES
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
    ivec4 tiles;
    bool live = sphere_tiles(batch * 256u + lane, tiles);
    if (live)
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
    if (live)
      for (int ty = tiles.y; ty <= tiles.w; ++ty)
        for (int tx = tiles.x; tx <= tiles.z; ++tx) {
          uint t = uint(tx + ty * u_tiles.x);
          tile_lists[s_base[t] + atomicAdd(s_tally[t], 1u)] = batch * 256u + lane;
        }
#endif
    barrier();
  }
}
#else
void main() {
  for (uint i = gl_GlobalInvocationID.x; i < u_count; i += gl_NumWorkGroups.x * 256u) {
    ivec4 tiles;
    if (!sphere_tiles(i, tiles)) continue;
    for (int ty = tiles.y; ty <= tiles.w; ++ty)
      for (int tx = tiles.x; tx <= tiles.z; ++tx) {
#ifndef BIN_SCATTER
        atomicAdd(tile_counts[tx + ty * u_tiles.x], 1u);
#else
        tile_lists[atomicAdd(tile_counts[tx + ty * u_tiles.x], 1u)] = i;
#endif
      }
  }
}
#endif
