// render/passes/splat.comp - marks the voxels of one tile that particle spheres cover (paper
// 001, sec. 3.1, 4.1, 4.4). Reads: particles (vec4 x, y, z, radius), the tile's particle list
// (SPLAT_FROM_LIST) or all particles (the paper's way). Writes: the tile's bits, atomicOr on
// 32-bit words, whole words at once where a chord covers them.
// Per (sphere, pixel): the pixel centre ray's chord through the sphere sets layers
// [layer(entry), layer(exit)]; with gap bridging (u_surface_only) only the entry and exit voxels
// are set where the chord's voxels lie closer than the gap g, since compress bridges what lies
// between (sec. 4.4): the spans come out the same as with whole chords.
// Threads: SPLAT_PER_PIXEL: a work group takes 64 spheres and shares their pixels out evenly,
// one thread per (sphere, pixel); otherwise one thread per sphere loops over its pixels.
// Cost: one ray-sphere test per (sphere, pixel) of the conservative footprint, one atomic per
// word touched.
layout(local_size_x = 64) in;

#include "render/perspective_grid.glsl"
#include "render/passes/bits.glsl"

layout(std430, binding = 0) buffer Bits { uint bits[]; };
layout(std430, binding = 1) readonly buffer Particles { vec4 particles[]; };
#ifdef SPLAT_FROM_LIST
layout(std430, binding = 2) readonly buffer TileList { uint tile_list[]; };
#endif

uniform ivec4 u_tile;          // x0, y0, width, height
uniform uint u_count;          // spheres to splat
uniform uint u_list_offset;    // first entry of this tile's list
uniform float u_gap;           // g (world units); surface-only spheres need 2 r < g
uniform uint u_surface_only;   // 1: entry and exit voxels only, where the gap allows

// The sphere in view space and its footprint clipped to the tile; false when it adds nothing.
bool load_sphere(uint i, out vec4 sphere, out ivec4 rect) {
#ifdef SPLAT_FROM_LIST
  vec4 p = particles[tile_list[u_list_offset + i]];
#else
  vec4 p = particles[i];
#endif
  sphere = vec4(0.0);
  rect = ivec4(0, 0, -1, -1);
  if (!valid_sphere(p)) return false;
  sphere = vec4(to_view(p.xyz), p.w);
  if (sphere.z + sphere.w <= u_near) return false;
  ivec4 r = sphere_pixels(sphere.xyz, sphere.w);
  rect = ivec4(max(r.xy, u_tile.xy), min(r.zw, u_tile.xy + u_tile.zw - 1));
  return rect.x <= rect.z && rect.y <= rect.w;
}

void set_layers(uint p, uint l0, uint l1) {
  uint w0 = l0 >> 5u, w1 = l1 >> 5u;
  for (uint w = w0; w <= w1; ++w) {
    uint lo = w == w0 ? (l0 & 31u) : 0u;
    uint hi = w == w1 ? (l1 & 31u) : 31u;
    atomicOr(bits[bit_word_index(p, w)], bit_range_mask(lo, hi));
  }
}

void splat_pixel(vec4 sphere, ivec2 pixel) {
  float z0, z1;
  vec3 ray = view_ray(pixel);
  if (!sphere_chord(ray, sphere.xyz, sphere.w, z0, z1)) return;
  if (z1 <= u_near || z0 >= u_grid_far) return;
  uint l0 = layer_index(max(z0, u_near));
  uint l1 = layer_index(z1);
  uint p = uint(pixel.x - u_tile.x) + uint(pixel.y - u_tile.y) * uint(u_tile.z);
  if (u_surface_only != 0u) {
    // Compress measures a gap between voxel centres: at most the chord plus one layer (a layer
    // at depth z is at most K_d z thick). The margin keeps float rounding from opening a gap
    // that would not close.
    float widest_gap = 2.0 * sphere.w + (exp2(u_log2_step) - 1.0) * z1 * length(ray);
    if (1.001 * widest_gap < u_gap) {
      atomicOr(bits[bit_word_index(p, l0 >> 5u)], 1u << (l0 & 31u));
      atomicOr(bits[bit_word_index(p, l1 >> 5u)], 1u << (l1 & 31u));
      return;
    }
  }
  set_layers(p, l0, l1);
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
    s_first[lane + 1u] = live ? uint(rect.z - rect.x + 1) * uint(rect.w - rect.y + 1) : 0u;
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
