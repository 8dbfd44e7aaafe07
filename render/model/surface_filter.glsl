// render/model/surface_filter.glsl - one iteration of the surface filter ([ZD15] sec. 3.4, 4.6)
// for one span, shared by the GPU filter pass (render/passes/filter.comp) and the CPU renderer
// (render/cpu/cpu_renderer.h): the reciprocal depth of its entry and its exit smoothed with the
// 3x3 binomial kernel over the points its links reach across (render/model/links.glsl). A
// point stops after n(z) iterations (constant world radius); it never moves more than u_radius
// from its span depth, nor past the midpoint to the neighbouring span of its column, and a
// span's entry never passes its exit.
//
// Host needs: links.glsl, surface_geometry.glsl and their needs, vec2 sd_raw_depths(uint) (the
// span depths), vec2 sd_depths(uint) (the previous iteration's), u_iteration (0-based),
// u_max_iterations, u_radius (world units), u_iteration_scale (n(z) = ceil(scale / z^2)).
#ifndef VX_MODEL_SURFACE_FILTER
#define VX_MODEL_SURFACE_FILTER

bool still_filtering(float depth) {
  float n = ceil(u_iteration_scale / (depth * depth));
  return float(u_iteration) < min(n, float(u_max_iterations));
}

// The kernel's weighted mean of 1/z: centre 4, direct neighbours 2, corners 1 (reached through
// a horizontal neighbour), over the points linked across only; returns the depth.
float smoothed_depth(SurfacePoint v, float depth) {
  float sum = 4.0f / depth;
  float weight = 4.0f;
  for (int dir = 0; dir < 2; ++dir) {
    if (!link_is_across(v, dir)) continue;
    SurfacePoint w = follow_link(v, dir);
    sum += 2.0f / point_depth(w);
    weight += 2.0f;
    for (int dir_y = 2; dir_y < 4; ++dir_y) {
      if (!link_is_across(w, dir_y)) continue;
      sum += 1.0f / point_depth(follow_link(w, dir_y));
      weight += 1.0f;
    }
  }
  for (int dir = 2; dir < 4; ++dir) {
    if (!link_is_across(v, dir)) continue;
    sum += 2.0f / point_depth(follow_link(v, dir));
    weight += 2.0f;
  }
  return weight / sum;
}

// The (entry, exit) depths of span s of pixel p after this iteration.
vec2 filter_span(ivec2 p, uint s) {
  uint first = sd_offset(p);
  uint last = first + sd_count(p) - 1u;
  vec2 original = sd_raw_depths(s);
  vec2 current = sd_depths(s);
  // Every point stays within the radius of where the voxelization put it, and on its side of
  // the midpoints to the neighbouring spans' current depths (the neighbours use the same
  // midpoints, so no two spans of a column can cross).
  float entry_lo = original.x - u_radius;
  float exit_hi = original.y + u_radius;
  if (s > first) entry_lo = max(entry_lo, 0.5f * (sd_depths(s - 1u).y + current.x));
  if (s < last) exit_hi = min(exit_hi, 0.5f * (current.y + sd_depths(s + 1u).x));
  vec2 next = current;
  if (still_filtering(original.x))
    next.x = clamp(smoothed_depth(surface_point(p, s, 0u), current.x), entry_lo,
                   original.x + u_radius);
  if (still_filtering(original.y))
    next.y = clamp(smoothed_depth(surface_point(p, s, 1u), current.y), original.y - u_radius,
                   exit_hi);
  // The two sides of a thin sheet move alike; where they would cross, they meet halfway.
  if (next.x > next.y) next = vec2(clamp(0.5f * (next.x + next.y), entry_lo, exit_hi));
  return next;
}

#endif
