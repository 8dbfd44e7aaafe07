// Refractive shading ([ZD15] sec. 3.5, Listing 2; render/gl/passes/shade_refractive.h): one thread per
// pixel, its ray's state kept in `rays` between dispatches (render/model/column_march.glsl).
// REFRACT_BEGIN starts every ray at the eye and gathers the depth bounds of each 8 x 8 block
// (for skipping empty space); REFRACT_MARCH advances each marching ray by at most
// u_march_budget column events and counts the rays still marching; REFRACT_RESOLVE sends the rays
// still marching to the environment, adds what each ray sees where it ended (over the footprint
// the neighbouring rays' ends give: end_light) and writes every pixel's colour.
layout(local_size_x = 64) in;

#include "render/gl/passes/shade_common.glsl"

// Per block of 8 x 8 columns (VX_BLOCK), four words (positive floats order as their bits): the
// largest ~bits of its nearest entry depth and the largest bits of its farthest exit depth,
// both 0 when the block holds no span; the largest bits of its columns' first entries (those of
// 3e38 when a column has no span) and the largest ~bits of their first exits. REFRACT_BEGIN
// gathers them.
layout(std430, binding = BLOCK_BOUNDS_BINDING) buffer BlockBounds { uint block_bounds[]; };
uniform int u_blocks_x;

uint block_word(ivec2 block) { return 4u * uint(block.x + block.y * u_blocks_x); }

vec2 sd_block_bounds(ivec2 block) {
  uint i = block_word(block);
  uint far_bits = block_bounds[i + 1u];
  if (far_bits == 0u) return vec2(3.0e38, -3.0e38);
  return vec2(uintBitsToFloat(~block_bounds[i]), uintBitsToFloat(far_bits));
}

vec2 sd_block_inside(ivec2 block) {
  uint i = block_word(block);
  uint exit_bits = block_bounds[i + 3u];
  if (exit_bits == 0u) return vec2(3.0e38, -3.0e38);
  return vec2(uintBitsToFloat(block_bounds[i + 2u]), uintBitsToFloat(~exit_bits));
}

struct RayRecord {
  vec4 origin;      // xyz; w: occlusion
  vec4 dir;         // xyz; w: anchor x
  vec4 throughput;  // xyz; w: anchor y
  vec4 color;       // xyz; w: anchor z
  ivec4 ints;       // pixel x, pixel y, hint,
                    // bounces | inside << 16 | marching << 17 | on_wall << 18 | left << 19
  ivec4 last;       // last_pixel x, y, last_span, last_end
};
layout(std430, binding = RAYS_BINDING) buffer Rays { RayRecord rays[]; };

vec4 sd_ray_end(ivec2 q);  // below, after the RayState of column_march.glsl it unpacks to

#include "render/model/column_march.glsl"
layout(std430, binding = MARCH_TALLY_BINDING) buffer MarchTally {
  uint active_rays;  // still marching after this dispatch
  uint events;       // column events in this dispatch, all rays
  uint most_events;  // by one ray
  uint most_spans;   // in one pixel (REFRACT_BEGIN)
};

uniform int u_march_budget;

RayRecord pack_ray(RayState s) {
  RayRecord r;
  r.origin = vec4(s.origin, s.occlusion);
  r.dir = vec4(s.dir, s.anchor.x);
  r.throughput = vec4(s.throughput, s.anchor.y);
  r.color = vec4(s.color, s.anchor.z);
  r.last = ivec4(s.last_pixel, s.last_span, int(s.last_end));
  r.ints = ivec4(s.pixel, s.hint,
                 s.bounces | (s.inside ? 1 << 16 : 0) | (s.marching ? 1 << 17 : 0) |
                     (s.on_wall ? 1 << 18 : 0) | (s.left ? 1 << 19 : 0));
  return r;
}

RayState unpack_ray(RayRecord r) {
  RayState s;
  s.origin = r.origin.xyz;
  s.occlusion = r.origin.w;
  s.dir = r.dir.xyz;
  s.throughput = r.throughput.xyz;
  s.color = r.color.xyz;
  s.anchor = vec3(r.dir.w, r.throughput.w, r.color.w);
  s.pixel = r.ints.xy;
  s.hint = r.ints.z;
  s.last_pixel = r.last.xy;
  s.last_span = r.last.z;
  s.last_end = uint(r.last.w);
  s.bounces = r.ints.w & 0xFFFF;
  s.inside = (r.ints.w & (1 << 16)) != 0;
  s.marching = (r.ints.w & (1 << 17)) != 0;
  s.on_wall = (r.ints.w & (1 << 18)) != 0;
  s.left = (r.ints.w & (1 << 19)) != 0;
  return s;
}

// Pixel q's ray_end as the neighbours' footprints read it (column_march.glsl's end_spread).
vec4 sd_ray_end(ivec2 q) { return ray_end(unpack_ray(rays[q.x + q.y * u_image.x])); }

void main() {
  uint i = thread_index();
  if (i >= u_thread_count) return;
#if defined(REFRACT_BEGIN)
  ivec2 p = thread_pixel(i);
  rays[i] = pack_ray(ray_start(p));
  uint n = sd_count(p);
  atomicMax(most_spans, n);
  uint b = block_word(p / VX_BLOCK);
  float wall = wall_depth(p);
  if (wall < 3.0e38) {
    atomicMax(block_bounds[b], ~floatBitsToUint(wall));
    atomicMax(block_bounds[b + 1u], floatBitsToUint(3.0e38));
  }
  if (n > 0u) {
    uint base = sd_offset(p);
    vec2 first = sd_depths(base);
    atomicMax(block_bounds[b], ~floatBitsToUint(first.x));
    atomicMax(block_bounds[b + 1u], floatBitsToUint(sd_depths(base + n - 1u).y));
    atomicMax(block_bounds[b + 2u], floatBitsToUint(first.x));
    atomicMax(block_bounds[b + 3u], ~floatBitsToUint(first.y));
  } else {
    atomicMax(block_bounds[b + 2u], floatBitsToUint(3.0e38));
  }
#elif defined(REFRACT_MARCH)
  RayState s = unpack_ray(rays[i]);
  if (!s.marching) return;
  int n = 0;
  for (; n < u_march_budget && s.marching; ++n) s = march_step(s);
  rays[i] = pack_ray(s);
  if (s.marching) atomicAdd(active_rays, 1u);
  atomicAdd(events, uint(n));
  atomicMax(most_events, uint(n));
#else
  RayState s = unpack_ray(rays[i]);
  if (s.marching) s = ray_leave(s);
  vec3 light = end_light(thread_pixel(i), ray_end(s), s.anchor, s.bounces <= u_bounces);
  shaded[i] = vec4(s.color + s.throughput * light, 1.0);
#endif
}
