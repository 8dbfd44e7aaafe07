// render/model/column_march.glsl - refraction by screen-space ray marching through the voxel
// columns ([ZD15] sec. 3.5 and Listing 2), shared by the GPU pass
// (render/gl/passes/shade_refractive.comp) and the C++ host (render/model/host.h: the CPU renderer
// and the reference).
//
// A ray starts at the eye through the pixel's centre and walks column by column (pixel by
// pixel) along its projection: in each column it finds the depths where it enters and leaves
// the column's pyramid, and the span boundaries (entry and exit depths) between them. Crossing a
// boundary that changes the ray's inside/outside state is a surface hit, and so is entering a
// column whose state at that depth differs from the ray's (a hit on the column's side,
// "in-between stored surface values", found from the parity of the boundaries before the
// depth: Listing 2's LSB test). At a hit the ray refracts with the stored normal (Fresnel
// reflection of the environment on entering; on leaving it follows the larger of the refracted
// and the reflected share, so near and past the critical angle it reflects and stays inside:
// total internal reflection), is absorbed (Beer-Lambert) and lit by scattering along every
// stretch inside, and leaves to the environment at the grid's boundary, or ends on the ground
// (opaque, the fluid resting on it) where it reaches the ground plane. After `u_bounces` hits
// past the first entry it goes straight on, still absorbed. What a ray sees where it ends (the
// environment or the walls) is added once the neighbouring pixels' rays have ended too
// (end_light): water spreads their rays apart, and each takes the mean over its footprint.
//
// One call of march_step() handles one event (a boundary crossed or a column left), so the
// caller bounds the work per shader invocation (llvmpipe stops an invocation after 65535 loop
// iterations) and resumes the RayState in a later dispatch.
//
// Host needs: links.glsl, surface_geometry.glsl, octahedral.glsl, lighting.glsl, shade_modes.glsl
// and their needs; u_bounces, u_near, u_grid_far, u_log2_step, u_ground_contact,
// u_wall_contact; vec2 sd_block_bounds(ivec2): the nearest entry and farthest exit depth in a
// block of VX_BLOCK^2 columns ((3e38, -3e38) when it holds no span; with a backdrop, a block
// with walls reaches from its nearest wall depth, or nearer entry, to 3e38, so that no ray skips
// a wall), and vec2 sd_block_inside(ivec2): the largest entry and the smallest exit of the
// columns' first spans (x = 3e38 when a column has none), both over the surface depths; vec4
// sd_ray_end(ivec2) (ray_end of pixel q's ray, once every ray has ended or paused);
// u_use_backdrop and, when it is set, vec4 sd_backdrop(ivec2) (the colour, and in the last
// component the walls' depth) and wall_light()'s needs (below).
#ifndef VX_MODEL_COLUMN_MARCH
#define VX_MODEL_COLUMN_MARCH

#define VX_HINT_SIDE -1  // origin on a side of the column just entered: compare its state
#define VX_HINT_FREE -2  // origin inside the column, state already settled
#define VX_BLOCK 8       // columns per side of the blocks the march skips when empty

struct RayState {
  vec3 origin;      // view space: the last event's point
  vec3 anchor;      // view space: the eye or the last surface hit, where the environment is
                    // looked up from (the grid's boundary is no place in the world)
  vec3 dir;         // view space, unit
  vec3 throughput;
  vec3 color;       // radiance gathered so far
  ivec2 pixel;      // the column the ray is in
  int hint;         // >= 0: origin lies on that boundary of the column; or VX_HINT_*
  ivec2 last_pixel; // the surface point the ray crossed last (span -1: none yet)
  int last_span;
  uint last_end;
  int bounces;      // hits left that bend the ray
  bool inside;
  bool marching;
  bool on_wall;     // ended on the walls at `origin`
  bool left;        // left to the environment from `anchor` along `dir`
  float occlusion;  // of the start pixel's front surface (deep AO), scales the scattering
};

uint boundary_count(ivec2 q) { return 2u * sd_count(q); }

// Boundary i of column q: the entry (i even) or exit (i odd) of span i / 2.
float boundary_depth(ivec2 q, uint i) {
  vec2 d = sd_depths(sd_offset(q) + i / 2u);
  return (i & 1u) == 0u ? d.x : d.y;
}

vec3 point_normal(SurfacePoint v) {
  uvec2 words = sd_normals(v.span);
  return decode_normal(v.end == 0u ? words.x : words.y);
}

// The normal at `hit` (view space) on boundary i of column q, interpolated bilinearly between
// the column's surface point and the points its links reach across towards the hit's side, so
// that the normal, and with it the refracted ray, varies smoothly across columns instead of
// jumping at their sides (where the links end, the column's own normal stands in).
vec3 boundary_normal(ivec2 q, uint i, vec3 hit) {
  SurfacePoint v = surface_point(q, sd_offset(q) + i / 2u, i & 1u);
  vec3 n = point_normal(v);
  vec2 xy = image_position(hit);
  vec2 f = clamp(xy - vec2(q) - vec2(0.5f), vec2(-0.5f), vec2(0.5f));
  int dir_x = f.x >= 0.0f ? 1 : 0;
  int dir_y = f.y >= 0.0f ? 3 : 2;
  vec3 nx = n;
  vec3 ny = n;
  vec3 nxy = n;
  if (link_is_across(v, dir_x)) {
    SurfacePoint w = follow_link(v, dir_x);
    nx = point_normal(w);
    nxy = link_is_across(w, dir_y) ? point_normal(follow_link(w, dir_y)) : nx;
  }
  if (link_is_across(v, dir_y)) ny = point_normal(follow_link(v, dir_y));
  float wx = abs(f.x);
  float wy = abs(f.y);
  vec3 mixed = mix(mix(n, nx, wx), mix(ny, nxy, wx), wy);
  float len = length(mixed);
  return world_to_view_direction(len > 1e-6f ? mixed / len : n);
}

// Boundaries of column q at depth <= z (or < z when strict).
uint boundaries_before(ivec2 q, float z, bool strict) {
  uint lo = 0u, hi = boundary_count(q);
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    float b = boundary_depth(q, mid);
    if (strict ? b < z : b <= z) lo = mid + 1u; else hi = mid;
  }
  return lo;
}

vec3 view_to_world_point(vec3 v) { return u_eye + view_to_world_direction(v); }

RayState ray_start(ivec2 p) {
  RayState s;
  s.origin = vec3(0.0f);
  s.anchor = vec3(0.0f);
  s.dir = normalize(view_ray_at(vec2(p) + vec2(0.5f)));
  s.throughput = vec3(1.0f);
  s.color = vec3(0.0f);
  s.pixel = p;
  s.hint = VX_HINT_FREE;
  s.last_pixel = p;
  s.last_span = -1;
  s.last_end = 0u;
  s.bounces = u_bounces + 1;
  s.inside = false;
  s.marching = true;
  s.on_wall = false;
  s.left = false;
  s.occlusion = pixel_occlusion(p);
  return s;
}

// The ray leaves to the environment (or ends on the ground, which is part of it): its host adds
// what it sees there (end_light).
RayState ray_leave(RayState s) {
  s.left = true;
  s.marching = false;
  return s;
}

// Height of view-space point v above the ground plane.
float above_ground(vec3 v) { return dot(view_to_world_point(v), u_env_up) - u_ground_height; }

// Where the walls of column q begin (render/backdrop.h), or 3e38 without a backdrop.
float wall_depth(ivec2 q) { return u_use_backdrop != 0 ? sd_backdrop(q).w : 3.0e38f; }

// Moves the ray to `point`, absorbing and scattering on the way when inside. The walls and the
// ground are opaque: a ray that reaches its column's walls (the backdrop's depth there: in
// screen space, as the fluid's own surfaces) ends on them; one that reaches the ground, from
// inside or outside, ends there. Without this, a ray in water lying on the ground would reach the
// union's bottom, just below the plane, and meet it as a free surface: past the critical angle
// it reflects totally and runs on inside the thin layer (the refraction's speckles).
RayState ray_advance(RayState s, vec3 point) {
  float wall = wall_depth(s.pixel);
  bool walled = point.z > wall;
  if (walled)
    point = s.origin.z >= wall ? s.origin : mix(s.origin, point, (wall - s.origin.z) / (point.z - s.origin.z));
  float h0 = above_ground(s.origin);
  float h1 = above_ground(point);
  bool grounded = h0 >= 0.0f && h1 < 0.0f;
  if (grounded) point = mix(s.origin, point, h0 / (h0 - h1));
  if (s.inside) {
    vec3 t = transmittance(length(point - s.origin));
    s.color += s.throughput * (vec3(1.0f) - t) * u_scatter_color * s.occlusion;
    s.throughput *= t;
  }
  s.origin = point;
  if (walled && !grounded) {
    s.on_wall = true;
    s.marching = false;
    return s;
  }
  return grounded ? ray_leave(s) : s;
}

// A hit at s.origin, the outward normal n (view space); `entering`: from outside into fluid.
RayState ray_interface(RayState s, vec3 n, bool entering) {
  // Leaving downwards where the fluid rests on the ground: no interface with air there; the ray
  // goes on inside, unbent, until ray_advance() ends it on the ground.
  if (!entering && above_ground(s.origin) < u_ground_contact &&
      dot(view_to_world_direction(s.dir), u_env_up) < 0.0f)
    return s;
  // The same where it rests against a wall: leaving towards its column's walls, just behind.
  if (!entering && s.dir.z > 0.0f && wall_depth(s.pixel) - s.origin.z < u_wall_contact) return s;
  if (s.bounces <= 0) {
    s.inside = entering;
    return s;
  }
  bool front = s.bounces > u_bounces;  // the first hit: the pixel's front surface
  s.bounces -= 1;
  s.anchor = s.origin;
  vec3 d = s.dir;
  if (entering) {
    if (!(dot(n, d) < 0.0f)) n = -d;  // a normal the ray cannot enter through: no bending
    // The front surface reflects over its footprint, as the translucent mode's does.
    vec2 footprint = front ? reflection_footprint(s.pixel, view_to_world_direction(d),
                                                  view_to_world_direction(n))
                           : vec2(0.0f, fresnel(-dot(n, d)));
    s.color += s.throughput * footprint.y *
               environment_over(view_to_world_point(s.origin),
                                view_to_world_direction(reflect(d, n)), footprint.x);
    s.throughput *= 1.0f - footprint.y;
    s.dir = normalize(refract(d, n, 1.0f / u_ior));
    s.inside = true;
  } else {
    if (!(dot(n, d) > 0.0f)) n = d;
    vec3 t = refract(d, -n, u_ior);
    float f = dot(t, t) == 0.0f ? 1.0f : fresnel(dot(normalize(t), n));
    if (f > 0.5f) {
      s.throughput *= f;
      s.dir = normalize(reflect(d, -n));  // (total) internal reflection: stays inside
    } else {
      s.throughput *= 1.0f - f;
      s.dir = normalize(t);
      s.inside = false;
    }
  }
  return s;
}

// Parameter along the ray where it crosses the column side k = x/z (axis 0) or y/z (axis 1);
// negative or infinite when it does not.
float side_crossing(vec3 o, vec3 d, float k, int axis) {
  float oa = axis == 0 ? o.x : o.y;
  float da = axis == 0 ? d.x : d.y;
  float denom = da - k * d.z;
  if (denom == 0.0f) return -1.0f;
  return (k * o.z - oa) / denom;
}

// Direction of the ray's projection across the columns along an axis: +1 when x/z (y/z) grows,
// -1 when it shrinks, 0 when it stays (rays through the eye). Constant along the ray.
int projected_direction(vec3 o, vec3 d, int axis) {
  float oa = axis == 0 ? o.x : o.y;
  float da = axis == 0 ? d.x : d.y;
  float g = da * o.z - oa * d.z;
  float size = abs(da * o.z) + abs(oa * d.z);
  if (!(abs(g) > 1e-6f * size)) return 0;
  return g > 0.0f ? 1 : -1;
}

RayState remember_crossing(RayState s, ivec2 q, uint i) {
  s.last_pixel = q;
  s.last_span = int(sd_offset(q) + i / 2u);
  s.last_end = i & 1u;
  return s;
}

// Entering column q from the side, the ray's state disagrees with the column's at its depth,
// between boundaries before - 1 and before. When one of the two is the surface the ray crossed
// last, continued across to this column by its link, the disagreement is that surface's
// staircase (each column holds it at one depth; the ray left it at a slant), not a new
// surface: returns that boundary, else -1.
int continued_surface(RayState s, ivec2 q, uint before) {
  if (s.last_span < 0) return -1;
  ivec2 step = q - s.last_pixel;
  int dir = -1;
  if (step.x == -1 && step.y == 0) dir = 0;
  if (step.x == 1 && step.y == 0) dir = 1;
  if (step.x == 0 && step.y == -1) dir = 2;
  if (step.x == 0 && step.y == 1) dir = 3;
  if (dir < 0) return -1;
  SurfacePoint v = surface_point(s.last_pixel, uint(s.last_span), s.last_end);
  if (!link_is_across(v, dir)) return -1;
  SurfacePoint w = follow_link(v, dir);
  uint i = (w.span - sd_offset(q)) * 2u + w.end;
  return (i == before || i + 1u == before) ? int(i) : -1;
}

// Where the ray leaves the pyramid of the pixels lo..hi (inclusive), or the grid's depth range.
struct PyramidExit {
  float s;   // ray parameter
  int side;  // 0: an x side, 1: a y side, 2: the near or far end of the grid
  int gx;    // projected_direction() along x and y
  int gy;
};

PyramidExit pyramid_exit(vec3 o, vec3 d, ivec2 lo, ivec2 hi) {
  PyramidExit e;
  e.s = 3.0e38f;
  e.side = 2;
  e.gx = projected_direction(o, d, 0);
  if (e.gx != 0) {
    float k = (2.0f * float(e.gx > 0 ? hi.x + 1 : lo.x) / float(u_image.x) - 1.0f) * u_tan_half.x;
    float t = side_crossing(o, d, k, 0);
    if (t >= 0.0f && t < e.s) {
      e.s = t;
      e.side = 0;
    }
  }
  e.gy = projected_direction(o, d, 1);  // +1: y/z grows, the ray moves up the rows
  if (e.gy != 0) {
    float k = (1.0f - 2.0f * float(e.gy > 0 ? lo.y : hi.y + 1) / float(u_image.y)) * u_tan_half.y;
    float t = side_crossing(o, d, k, 1);
    if (t >= 0.0f && t < e.s) {
      e.s = t;
      e.side = 1;
    }
  }
  float limit = d.z > 0.0f ? (u_grid_far - o.z) / d.z : (d.z < 0.0f ? (u_near - o.z) / d.z : 3.0e38f);
  if (limit < e.s) {
    e.s = max(limit, 0.0f);
    e.side = 2;
  }
  return e;
}

// A block of VX_BLOCK x VX_BLOCK columns that the ray crosses without meeting a boundary is
// crossed in one step (outside: no surface between the depths where the ray enters and leaves
// the block's pyramid; inside: every column's first span holds them), absorbed on the way when
// inside: the march skips empty space and deep water without changing what it finds.
RayState skip_block(RayState s, PyramidExit e, ivec2 b0, ivec2 b1) {
  vec3 p = s.origin + e.s * s.dir;
  s = ray_advance(s, p);
  if (!s.marching) return s;
  if (e.side == 2) return ray_leave(s);
  vec2 xy = image_position(p);
  ivec2 next;
  if (e.side == 0) next = ivec2(e.gx > 0 ? b1.x + 1 : b0.x - 1, clamp(int(floor(xy.y)), b0.y, b1.y));
  else next = ivec2(clamp(int(floor(xy.x)), b0.x, b1.x), e.gy > 0 ? b0.y - 1 : b1.y + 1);
  if (!in_image(next)) return ray_leave(s);
  s.pixel = next;
  s.hint = VX_HINT_SIDE;
  return s;
}

// One event: the next boundary of the current column, the step into the next column, or the
// step across a block: outside the fluid one with no surface in the ray's depth range there,
// inside it one whose columns' first spans all hold that depth range (the ray stays inside
// every column it crosses: none of their boundaries lies on its way).
RayState march_step(RayState s) {
  ivec2 q = s.pixel;
  vec3 o = s.origin;
  vec3 d = s.dir;
  ivec2 b0 = (q / VX_BLOCK) * VX_BLOCK;
  ivec2 b1 = min(b0 + ivec2(VX_BLOCK - 1), u_image - ivec2(1));
  if (!s.inside) {
    vec2 bounds = sd_block_bounds(q / VX_BLOCK);
    PyramidExit block = pyramid_exit(o, d, b0, b1);
    float z_block = o.z + block.s * d.z;
    if (max(o.z, z_block) < bounds.x || min(o.z, z_block) > bounds.y)
      return skip_block(s, block, b0, b1);
  } else {
    // The ray's depth is monotonic along it: both ends in the range hold it all. The cheap test
    // of its start comes first, so that a splash, whose blocks rarely qualify, pays little.
    vec2 held = sd_block_inside(q / VX_BLOCK);
    if (o.z > held.x && o.z < held.y) {
      PyramidExit block = pyramid_exit(o, d, b0, b1);
      float z_block = o.z + block.s * d.z;
      if (z_block > held.x && z_block < held.y) return skip_block(s, block, b0, b1);
    }
  }
  // Where the ray leaves this column's pyramid (or the grid's depth range).
  PyramidExit column = pyramid_exit(o, d, q, q);
  float s_end = column.s;
  ivec2 next_pixel = ivec2(-1);
  if (column.side == 0) next_pixel = q + ivec2(column.gx, 0);
  if (column.side == 1) next_pixel = q + ivec2(0, -column.gy);
  bool forward = d.z >= 0.0f;
  float z_end = o.z + s_end * d.z;

  // The next boundary the ray may cross in this column.
  int next;
  if (s.hint >= 0) {
    next = forward ? s.hint + 1 : s.hint - 1;
  } else {
    uint before = boundaries_before(q, o.z, false);
    bool column_inside = (before & 1u) == 1u;
    if (s.hint == VX_HINT_SIDE && column_inside != s.inside) {
      s.hint = VX_HINT_FREE;
      int continued = continued_surface(s, q, before);
      if (continued >= 0) return remember_crossing(s, q, uint(continued));
      // Within one layer of a boundary the column's state is below the voxelization's
      // resolution: the ray grazes the surface there rather than hitting its side.
      uint nb = boundary_count(q);
      float layer = o.z * (exp2(u_log2_step) - 1.0f);
      if ((before > 0u && o.z - boundary_depth(q, before - 1u) < layer) ||
          (before < nb && boundary_depth(q, before) - o.z < layer))
        return s;
      // A hit on the column's side: the normal of the boundary nearest in depth (none in an
      // empty column: the ray leaves the fluid unbent).
      vec3 n = vec3(0.0f);
      if (nb > 0u) {
        uint i = before < nb ? before : nb - 1u;
        if (before > 0u && before < nb && o.z - boundary_depth(q, before - 1u) < boundary_depth(q, before) - o.z)
          i = before - 1u;
        n = boundary_normal(q, i, o);
        s = remember_crossing(s, q, i);
      }
      return ray_interface(s, n, column_inside);
    }
    next = forward ? int(before) : int(boundaries_before(q, o.z, true)) - 1;
  }
  if (next >= 0 && uint(next) < boundary_count(q)) {
    float b = boundary_depth(q, uint(next));
    if (forward ? b <= z_end : b >= z_end) {
      float t = d.z != 0.0f ? (b - o.z) / d.z : 0.0f;
      s = ray_advance(s, o + t * d);
      if (!s.marching) return s;
      s.hint = next;
      s = remember_crossing(s, q, uint(next));
      bool inside_after = forward ? (next & 1) == 0 : (next & 1) == 1;
      if (inside_after == s.inside) return s;  // agrees with the ray's state: nothing to hit
      return ray_interface(s, boundary_normal(q, uint(next), s.origin), inside_after);
    }
  }
  s = ray_advance(s, o + s_end * d);
  if (!s.marching) return s;
  if (!in_image(next_pixel)) return ray_leave(s);
  s.pixel = next_pixel;
  s.hint = VX_HINT_SIDE;
  return s;
}

// How a ray ended, in the form its neighbours read it (sd_ray_end): on the walls, (the image
// position where it ended, 0, VX_END_WALLS); leaving to the environment, or still marching (the
// resolve step sends it there), (the direction it left along, VX_END_LEFT); else 0.
#define VX_END_WALLS 1.0f
#define VX_END_LEFT 2.0f

vec4 ray_end(RayState s) {
  if (s.on_wall) return vec4(image_position(s.origin), 0.0f, VX_END_WALLS);
  if (s.left || s.marching) return vec4(s.dir, VX_END_LEFT);
  return vec4(0.0f);
}

// Half the largest difference between `end` (ray_end's form) of pixel p's ray and the ends of
// its four neighbours' rays that ended alike: the distance between where they ended on the walls
// (pixels), or the angle between the directions they left along (radians).
float end_spread(ivec2 p, vec4 end) {
  float spread = 0.0f;
  for (int k = 0; k < 4; ++k) {
    ivec2 q = p + (k < 2 ? ivec2(2 * k - 1, 0) : ivec2(0, 2 * k - 5));  // left, right, up, down
    if (!in_image(q)) continue;
    vec4 other = sd_ray_end(q);
    if (other.w != end.w) continue;
    float d = end.w == VX_END_WALLS ? length(vec2(other) - vec2(end))
                                    : acos(clamp(dot(vec3(other), vec3(end)), -1.0f, 1.0f));
    spread = max(spread, 0.5f * d);
  }
  return spread;
}

// The walls' light where rays end on them. Water bends neighbouring pixels' rays apart, so that
// one ray a pixel samples the walls' picture more sparsely than a pixel: where that picture has
// edges finer than the rays' spread (a corner, a rim, the spheres' bumps) single pixels take the
// colour from across the edge, the refracted picture's speckles. So each ray takes the mean of
// the walls over its footprint, as a GPU picks a texture's level of detail from neighbouring
// pixels' coordinates: the half width is half the largest distance to where the four
// neighbours' rays ended on the walls, read from the backdrop's pyramid (render/backdrop.h,
// backdrop_pyramid: level 0 the backdrop, each level above the 2x2 means of the one below,
// premultiplied by the share of wall pixels, all in one array), trilinearly.
//
// Host needs: vec4 sd_backdrop_texel(uint) (the pyramid's entries).
#define VX_BACKDROP_LEVELS 8  // render/backdrop.h's kBackdropLevels: footprints up to 64 pixels

ivec2 backdrop_level_size(int level) {
  return ivec2((u_image.x + (1 << level) - 1) >> level, (u_image.y + (1 << level) - 1) >> level);
}

// Texel t, clamped, of the level of `size` that starts at `offset` in the pyramid: (rgb times the
// wall share, the share); level 0 holds the backdrop's (rgb, depth).
vec4 backdrop_texel(uint offset, ivec2 size, ivec2 t) {
  t = clamp(t, ivec2(0), size - ivec2(1));
  vec4 b = sd_backdrop_texel(offset + uint(t.x) + uint(t.y) * uint(size.x));
  if (offset > 0u) return b;
  return b.w < 3.0e38f ? vec4(vec3(b), 1.0f) : vec4(0.0f);
}

// Bilinear between level `level`'s texels around image position xy (level 0 pixels).
vec4 backdrop_bilinear(int level, vec2 xy) {
  uint offset = 0u;
  for (int l = 0; l < level; ++l) {
    ivec2 below = backdrop_level_size(l);
    offset += uint(below.x) * uint(below.y);
  }
  ivec2 size = backdrop_level_size(level);
  vec2 t = xy / float(1 << level) - vec2(0.5f);
  ivec2 t0 = ivec2(floor(t));
  vec2 f = t - floor(t);
  vec4 top = mix(backdrop_texel(offset, size, t0),
                 backdrop_texel(offset, size, t0 + ivec2(1, 0)), f.x);
  vec4 bottom = mix(backdrop_texel(offset, size, t0 + ivec2(0, 1)),
                    backdrop_texel(offset, size, t0 + ivec2(1, 1)), f.x);
  return mix(top, bottom, f.y);
}

// The walls' colour seen by the ray of pixel p that ended on them at image position `land`;
// wider footprints than the pyramid's top but one (a grazing ray) take that level's.
vec3 wall_light(ivec2 p, vec2 land) {
  float radius = max(0.5f, end_spread(p, vec4(land, 0.0f, VX_END_WALLS)));
  float lod = min(log2(2.0f * radius), float(VX_BACKDROP_LEVELS - 2));
  int level = int(floor(lod));
  vec4 c =
      mix(backdrop_bilinear(level, land), backdrop_bilinear(level + 1, land), lod - float(level));
  if (c.w > 0.0f) return vec3(c) / c.w;
  ivec2 q = clamp(ivec2(floor(land)), ivec2(0), u_image - ivec2(1));
  return vec3(sd_backdrop(q));
}

// The environment's light seen by the ray of pixel p that left to it from `anchor` along `dir`
// (view space). Water bends the environment's picture as it bends the walls', and the ground's
// checker is as fine: a ray that met the fluid (`bent`) takes the environment's mean over its
// footprint (environment_over); one that did not, the point the other modes' background takes.
vec3 environment_light(ivec2 p, vec3 anchor, vec3 dir, bool bent) {
  float spread = bent ? end_spread(p, vec4(dir, VX_END_LEFT)) : 0.0f;
  return environment_over(view_to_world_point(anchor), view_to_world_direction(dir), spread);
}

// What the ray of pixel p sees where it ended (`end` in ray_end's form; `anchor` and `bent` as
// environment_light takes them), before its throughput.
vec3 end_light(ivec2 p, vec4 end, vec3 anchor, bool bent) {
  if (end.w == VX_END_WALLS) return wall_light(p, vec2(end));
  if (end.w == VX_END_LEFT) return environment_light(p, anchor, vec3(end), bent);
  return vec3(0.0f);
}

// At most `budget` events.
RayState march(RayState s, int budget) {
  for (int i = 0; i < budget; ++i) {
    if (!s.marching) break;
    s = march_step(s);
  }
  return s;
}

#endif
