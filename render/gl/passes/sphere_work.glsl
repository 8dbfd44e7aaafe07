// render/gl/passes/sphere_work.glsl - how much splat work a sphere is, shared by the binning and
// the splat passes so that both sort every sphere the same way.
//
// Why: llvmpipe stops a shader invocation's loops after 65535 iterations in all (Mesa's
// LP_MAX_TGSI_LOOP_ITERATIONS, shared by every loop of the shader), and on any GPU one thread
// marking a sphere that covers the screen would run for ages. So spheres are split in two:
//   small: footprint <= kSmallArea pixels, depth extent <= kSmallWords words, their product
//          <= kSmallWork: splatted from the tile lists, one thread per (sphere, pixel) or per
//          sphere, a bounded loop each;
//   large: everything else (spheres near or around the camera, spheres bigger than the
//          screen): splatted by render/gl/passes/splat_large.comp, cut into items of one pixel and
//          at most kLargeBlockWords words, spread over as many threads as there are items.
// Needs render/gl/perspective_grid.glsl.

const uint kSmallArea = 1024u;
const uint kSmallWords = 64u;
const uint kSmallWork = 8192u;
const uint kLargeBlockWords = 32u;

// The sphere of particle p in view space, or false when it adds no voxel (invalid, or wholly
// before the near plane).
bool view_sphere(vec4 p, out vec4 sphere) {
  sphere = vec4(0.0);
  if (!valid_sphere(p)) return false;
  sphere = vec4(to_view(p.xyz), p.w);
  return sphere.z + sphere.w > u_near;
}

// Words of a column the sphere's chords can touch: its depth extent in layers, in words.
uint sphere_words(vec4 sphere) {
  uint first = layer_index(max(sphere.z - sphere.w, u_near)) >> 5u;
  uint last = layer_index(sphere.z + sphere.w) >> 5u;
  return last - first + 2u;  // one spare: float rounding may move a chord a layer out
}

uint rect_area(ivec4 rect) {
  return rect.x > rect.z || rect.y > rect.w ? 0u : uint(rect.z - rect.x + 1) * uint(rect.w - rect.y + 1);
}

// `rect`: the sphere's pixels on the whole screen (sphere_pixels), not clipped to a tile, so that
// the answer does not depend on the tiling.
bool sphere_is_large(vec4 sphere, ivec4 rect) {
  uint area = rect_area(rect);
  uint words = sphere_words(sphere);
  return area > kSmallArea || words > kSmallWords || area * words > kSmallWork;
}

// Items of a large sphere in a tile: one per (pixel, block of kLargeBlockWords words).
uint large_sphere_blocks(vec4 sphere) {
  return (sphere_words(sphere) + kLargeBlockWords - 1u) / kLargeBlockWords;
}
