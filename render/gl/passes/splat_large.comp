// render/gl/passes/splat_large.comp - splats the large spheres (render/gl/passes/sphere_work.glsl:
// spheres near or around the camera, spheres bigger than the screen) into one tile, with the
// work cut into items of one pixel and at most kLargeBlockWords words of its chord, so every
// thread's loops stay short however big the sphere ([ZD15] sec. 4.1, 4.4).
//   LARGE_ITEMS: items[j] = the large sphere j's items in this tile (pixels in the tile x word
//     blocks); a prefix sum then gives each sphere its first item;
//   default: one thread per item: finds its sphere by binary search over the item offsets and
//     marks its words with atomicOr, as splat.comp would.
// Reads: particles, the large list (from BinPass). Writes: items, or the tile's bits.
// Cost: one ray-sphere test and up to kLargeBlockWords atomics per item; log2(large spheres)
// reads to find the sphere. The C++ side cuts the large list into batches whose items a uint
// counts, and the items into dispatches of at most 8 per thread.
layout(local_size_x = 64) in;

#include "render/gl/perspective_grid.glsl"
#include "render/gl/passes/bits.glsl"
#include "render/gl/passes/sphere_work.glsl"
#include "render/gl/passes/splat_common.glsl"

layout(std430, binding = PARTICLES_BINDING) readonly buffer Particles { vec4 particles[]; };
layout(std430, binding = LIST_BINDING) readonly buffer LargeList { uint large_list[]; };
layout(std430, binding = ITEMS_BINDING) buffer Items {
  uint items[];  // per sphere; then its first item
};

uniform uint u_large_first;  // first large sphere of this batch in the large list
uniform uint u_large;        // large spheres in this batch
uniform uint u_item_first;   // default pass: first item of this dispatch
uniform uint u_items;        // default pass: items in this dispatch

// The large sphere j in view space, its pixels in the tile and its word blocks.
bool large_sphere(uint j, out vec4 sphere, out ivec4 rect, out uint blocks) {
  rect = ivec4(0, 0, -1, -1);
  blocks = 0u;
  if (!view_sphere(particles[large_list[u_large_first + j]], sphere)) return false;
  ivec4 r = sphere_pixels(sphere.xyz, sphere.w);
  rect = ivec4(max(r.xy, u_tile.xy), min(r.zw, u_tile.xy + u_tile.zw - 1));
  blocks = large_sphere_blocks(sphere);
  return rect.x <= rect.z && rect.y <= rect.w;
}

#ifdef LARGE_ITEMS
void main() {
  for (uint j = gl_GlobalInvocationID.x; j < u_large; j += gl_NumWorkGroups.x * 64u) {
    vec4 sphere;
    ivec4 rect;
    uint blocks;
    items[j] = large_sphere(j, sphere, rect, blocks) ? rect_area(rect) * blocks : 0u;
  }
}
#else
void main() {
  for (uint i = gl_GlobalInvocationID.x; i < u_items; i += gl_NumWorkGroups.x * 64u) {
    uint t = u_item_first + i;
    // The sphere j with items[j] <= t < items[j + 1] (items holds u_large + 1 offsets).
    uint lo = 0u, hi = u_large;
    while (hi - lo > 1u) {
      uint mid = (lo + hi) >> 1u;
      if (items[mid] <= t) lo = mid; else hi = mid;
    }
    vec4 sphere;
    ivec4 rect;
    uint blocks;
    large_sphere(lo, sphere, rect, blocks);
    uint local = t - items[lo];
    uint block = local % blocks, pixel = local / blocks;
    uint width = uint(rect.z - rect.x + 1);
    Chord c;
    if (!pixel_chord(sphere, rect.xy + ivec2(pixel % width, pixel / width), c)) continue;
    if (c.surface) {
      if (block == 0u) {
        set_layer(c.p, c.l0);
        set_layer(c.p, c.l1);
      }
    } else {
      uint first = (c.l0 >> 5u) + block * kLargeBlockWords;
      set_layers_in_words(c.p, c.l0, c.l1, first, first + kLargeBlockWords - 1u);
    }
  }
}
#endif
