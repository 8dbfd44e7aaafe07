// render/gl/passes/splat.comp - marks the voxels of one tile that particle spheres cover (paper
// 001, sec. 3.1, 4.1, 4.4). Reads: particles (vec4 x, y, z, radius), the tile's particle list
// (SPLAT_FROM_LIST) or all particles (the paper's way). Writes: the tile's bits, atomicOr on
// 32-bit words, whole words at once where a chord covers them.
// Per (sphere, pixel): the pixel centre ray's chord through the sphere sets layers
// [layer(entry), layer(exit)]; with gap bridging (u_surface_only) only the entry and exit voxels
// are set where the chord's voxels lie closer than the gap g, since compress bridges what lies
// between (sec. 4.4): the spans come out the same as with whole chords.
// Threads: SPLAT_PER_PIXEL: a work group takes 64 spheres and shares their pixels out evenly,
// one thread per (sphere, pixel); otherwise one thread per sphere loops over its pixels.
// Small spheres only (render/gl/passes/sphere_work.glsl), so every thread's loops stay short.
// Cost: one ray-sphere test per (sphere, pixel) of the conservative footprint, one atomic per
// word touched.
layout(local_size_x = 64) in;

#include "render/gl/perspective_grid.glsl"
#include "render/gl/passes/bits.glsl"
#include "render/gl/passes/sphere_work.glsl"
#include "render/gl/passes/splat_common.glsl"

layout(std430, binding = PARTICLES_BINDING) readonly buffer Particles { vec4 particles[]; };
#ifdef SPLAT_FROM_LIST
layout(std430, binding = LIST_BINDING) readonly buffer TileList { uint tile_list[]; };
#endif

uniform uint u_count;          // spheres to splat
uniform uint u_list_offset;    // first entry of this tile's list

// The small sphere in view space and its footprint clipped to the tile; false when it adds
// nothing here. The tile lists hold small spheres only; without them, large ones are skipped
// here and splatted by splat_large.comp.
bool load_sphere(uint i, out vec4 sphere, out ivec4 rect) {
#ifdef SPLAT_FROM_LIST
  vec4 p = particles[tile_list[u_list_offset + i]];
#else
  vec4 p = particles[i];
#endif
  rect = ivec4(0, 0, -1, -1);
  if (!view_sphere(p, sphere)) return false;
  ivec4 r = sphere_pixels(sphere.xyz, sphere.w);
#ifndef SPLAT_FROM_LIST
  if (sphere_is_large(sphere, r)) return false;
#endif
  rect = ivec4(max(r.xy, u_tile.xy), min(r.zw, u_tile.xy + u_tile.zw - 1));
  return rect.x <= rect.z && rect.y <= rect.w;
}

#ifdef SPLAT_PER_PIXEL
shared vec4 s_sphere[64];
shared ivec4 s_rect[64];
shared uint s_first[65];  // exclusive prefix sum of the spheres' pixel counts

void main() {
  uint batches = (u_count + 63u) / 64u;
  uint lane = gl_LocalInvocationID.x;
  // Loop bounds depend on the work group only, so the barriers are uniform.
  for (uint batch = gl_WorkGroupID.x; batch < batches; batch += gl_NumWorkGroups.x) {
    uint i = batch * 64u + lane;
    vec4 sphere;
    ivec4 rect;
    bool live = i < u_count && load_sphere(i, sphere, rect);
    s_sphere[lane] = sphere;
    s_rect[lane] = rect;
    s_first[lane + 1u] = live ? rect_area(rect) : 0u;
    barrier();
    if (lane == 0u) {
      s_first[0] = 0u;
      for (uint k = 1u; k <= 64u; ++k) s_first[k] += s_first[k - 1u];
    }
    barrier();
    uint total = s_first[64];
    for (uint k = lane; k < total; k += 64u) {
      // The sphere j with s_first[j] <= k < s_first[j + 1].
      uint lo = 0u, hi = 64u;
      while (hi - lo > 1u) {
        uint mid = (lo + hi) >> 1u;
        if (s_first[mid] <= k) lo = mid; else hi = mid;
      }
      ivec4 r = s_rect[lo];
      uint local = k - s_first[lo];
      uint w = uint(r.z - r.x + 1);
      splat_pixel(s_sphere[lo], r.xy + ivec2(local % w, local / w));
    }
    barrier();
  }
}
#else
void main() {
  for (uint i = gl_GlobalInvocationID.x; i < u_count; i += gl_NumWorkGroups.x * 64u) {
    vec4 sphere;
    ivec4 rect;
    if (!load_sphere(i, sphere, rect)) continue;
    for (int y = rect.y; y <= rect.w; ++y)
      for (int x = rect.x; x <= rect.z; ++x) splat_pixel(sphere, ivec2(x, y));
  }
}
#endif
