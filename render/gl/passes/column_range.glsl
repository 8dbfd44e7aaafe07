// render/gl/passes/column_range.glsl - the chunks of a pixel's column that can hold fluid: its
// 16x16 block's depth bounds (render/gl/passes/depth_bounds.glsl), the large spheres', and from the
// near plane on when the ray starts inside inner-full cells. The column clear zeroes exactly
// these chunks and the compress pass reads exactly these, so the rest of the grid is never
// touched. A margin of a layer and of 1e-5 of the depth on each side absorbs float rounding
// between the bounds and the splat's chords. Needs render/gl/perspective_grid.glsl and
// render/gl/passes/cell_march.glsl; the pass defines DEPTH_BOUNDS_BINDING, the bounds buffer's.

#include "render/gl/passes/depth_bounds.glsl"

layout(std430, binding = DEPTH_BOUNDS_BINDING) readonly buffer DepthBounds {
  uvec2 depth_bounds[];
};

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
  first = (max(layer_index(nearest * (1.0 - 1e-5)), 1u) - 1u) >> 7u;
  last = min(layer_index(farthest * (1.0 + 1e-5)) + 1u, u_layers - 1u) >> 7u;
  return true;
}
