// render/model/surface_filter.glsl - the surface filter ([ZD15] sec. 3.4, 4.6) for one span,
// shared by the GPU filter pass (render/gl/passes/filter.comp) and the CPU renderer
// (render/cpu/cpu_renderer.h): the reciprocal depth of its entry and its exit smoothed over
// the points its links reach across (render/model/links.glsl) as n(z) iterations of the 3x3
// binomial kernel would smooth it (constant world radius), in four passes instead of n:
//   pass 0  along the row: the binomial weights of n / 2 iterations of [1 2 1] / 4, walked out
//           along the left and right links (to 4 standard deviations: the weights left out
//           sum to under 1e-4);
//   pass 1  along the column, over pass 0's values, n iterations' weights;
//   pass 2  along the row again, the other n / 2;
//   pass 3  the bounds: no point ends more than u_radius from its span depth, nor past the
//           midpoint to the neighbouring span of its column, and a span's entry never passes
//           its exit (where they would cross, they meet halfway).
// On a surface linked all round this is the iterated kernel exactly (n iterations of [1 2 1]
// are the binomial of order 2n, and the kernel is a row kernel times a column kernel, its
// corners reached through a row link, then a column link); where links end on one side a line
// is fitted instead of the mean taken (binomial_walk; the iterated kernel averages the points
// present, which moves a sloping surface at its edges), and the bounds hold once at the end
// instead of after every iteration. The rows come twice because a column whose column links
// break (a crease seen as a staircase) would otherwise keep the rows' smoothing only, unlike
// its neighbours: vertical streaks; the iterated kernel goes round such breaks. Work per end:
// about 8 sqrt(m / 2) neighbour reads for a pass of m iterations (n = 32: 80) against 8 n (256).
//
// Host needs: links.glsl, surface_geometry.glsl and their needs, vec2 sd_raw_depths(uint) (the
// span depths), vec2 sd_depths(uint) (the previous pass's), u_filter_pass (0 .. 3),
// u_max_iterations, u_radius (world units), u_iteration_scale (n(z) = ceil(scale / z^2)).
#ifndef VX_MODEL_SURFACE_FILTER
#define VX_MODEL_SURFACE_FILTER

// The iterations n(z) of a point at span depth z, capped.
int filter_iterations(float depth) {
  return int(min(ceil(u_iteration_scale / (depth * depth)), float(u_max_iterations)));
}

// 1/z at v of the line fitted by weighted least squares to 1/z over the points linked across
// from v along directions dir_minus and dir_plus (binomial weights C(2n, n + k) / C(2n, n) at
// k steps); returns the depth. Where the links go on equally far both ways the line's value at
// v is the weighted mean, the binomial kernel itself; where they end on one side (a
// silhouette, a crest, a fold) the fit still leaves a sloping surface (a plane: 1/z linear on
// the screen) where it is, where the weighted mean would pull v towards the side that goes on:
// a step along every edge that the normals saw as streaks and dots (docs/benchmarks.md). The
// sums are of differences from v's own 1/z, which float holds at every scale.
float binomial_walk(SurfacePoint v, int n, int dir_minus, int dir_plus) {
  if (n <= 0) return point_depth(v);
  int reach = min(n, int(ceil(4.0f * sqrt(0.5f * float(n)))));
  float f0 = 1.0f / point_depth(v);
  float s0 = 1.0f, s1 = 0.0f, s2 = 0.0f, sg = 0.0f, skg = 0.0f;  // sums of w, wk, wk^2, wg, wkg
  for (int side = 0; side < 2; ++side) {
    int dir = side == 0 ? dir_minus : dir_plus;
    float sign = side == 0 ? -1.0f : 1.0f;
    SurfacePoint w = v;
    float wk = 1.0f;
    for (int k = 0; k < reach; ++k) {
      if (!link_is_across(w, dir)) break;
      w = follow_link(w, dir);
      wk *= float(n - k) / float(n + k + 1);
      float t = sign * float(k + 1);
      float g = 1.0f / point_depth(w) - f0;
      s0 += wk;
      s1 += wk * t;
      s2 += wk * t * t;
      sg += wk * g;
      skg += wk * t * g;
    }
  }
  // v itself is in the fit, so det > 0 once one neighbour is: (1 + sum w) sum wt^2 > (sum wt)^2.
  float det = s0 * s2 - s1 * s1;
  float inv = det > 0.0f ? f0 + (s2 * sg - s1 * skg) / det : f0;
  return inv > 0.0f ? 1.0f / inv : point_depth(v);
}

// Pass 2: span s's smoothed depths within their bounds.
vec2 bounded_span(ivec2 p, uint s) {
  uint first = sd_offset(p);
  uint last = first + sd_count(p) - 1u;
  vec2 original = sd_raw_depths(s);
  vec2 smoothed = sd_depths(s);
  // The neighbouring spans use the same midpoints, so no two spans of a column can cross.
  float entry_lo = original.x - u_radius;
  float exit_hi = original.y + u_radius;
  if (s > first) entry_lo = max(entry_lo, 0.5f * (sd_depths(s - 1u).y + smoothed.x));
  if (s < last) exit_hi = min(exit_hi, 0.5f * (smoothed.y + sd_depths(s + 1u).x));
  vec2 next = vec2(clamp(smoothed.x, entry_lo, original.x + u_radius),
                   clamp(smoothed.y, original.y - u_radius, exit_hi));
  // The two sides of a thin sheet move alike; where they would cross, they meet halfway.
  if (next.x > next.y) next = vec2(clamp(0.5f * (next.x + next.y), entry_lo, exit_hi));
  return next;
}

// The (entry, exit) depths of span s of pixel p after pass u_filter_pass: 0 the rows with half
// the iterations, 1 the columns with all, 2 the rows with the other half, 3 the bounds.
vec2 filter_span(ivec2 p, uint s) {
  if (u_filter_pass == 3u) return bounded_span(p, s);
  int dir_minus = u_filter_pass == 1u ? 2 : 0;
  vec2 original = sd_raw_depths(s);
  ivec2 n = ivec2(filter_iterations(original.x), filter_iterations(original.y));
  if (u_filter_pass == 0u) n = n / 2;
  if (u_filter_pass == 2u) n = n - n / 2;
  return vec2(binomial_walk(surface_point(p, s, 0u), n.x, dir_minus, dir_minus + 1),
              binomial_walk(surface_point(p, s, 1u), n.y, dir_minus, dir_minus + 1));
}

#endif
