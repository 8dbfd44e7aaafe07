// render/model/surface_geometry.glsl - positions of surface points and the Sobel normal along the
// surface links ([ZD15] sec. 3.4: "Sobel operator on connected surface depths"), shared by the GPU
// normals pass and the C++ host (render/model/host.h: the CPU renderer and the reference).
//
// The 3x3 neighbourhood of a surface point is reached through its links: the four direct
// neighbours by one link, the corners by a horizontal link then a vertical one. Where a link
// stays in the point's own column (SELF: the span's silhouette, OWN: a bubble wall), the surface
// turns there: its sample is the wall point half a pixel over, halfway in depth between the
// two linked points, and a corner beyond a wall is that wall point again; where the link was
// cut at a fold (links.glsl) the surface goes on out of sight, and its sample is the point
// half a pixel over at v's own depth. The normal is the
// cross product of the two Sobel tangents, turned to face the eye at an entry and away from it
// at an exit (so every stored normal points out of the fluid), in world space.
//
// Host needs: links.glsl and its needs (u_fold_step also marks crests, on_crest), octahedral.glsl,
// uint sd_normal_word(uint span, uint end) (the first dispatch's, for crest_normal_word), vec2
// sd_depths(uint) (the surface depths the normals are built on: filtered or not), float
// sd_wall_depth(ivec2) (the view depth where the pixel's walls begin, render/backdrop.h; 3e38
// where none or without walls), u_image, u_tan_half, u_right, u_up, u_forward.
#ifndef VX_MODEL_SURFACE_GEOMETRY
#define VX_MODEL_SURFACE_GEOMETRY

// View-space ray (depth component 1) through image position xy in pixels (pixel (x, y) spans
// [x, x + 1) x [y, y + 1); its centre is (x + 0.5, y + 0.5)).
vec3 view_ray_at(vec2 xy) {
  vec2 ndc = vec2(2.0f * xy.x / float(u_image.x) - 1.0f, 1.0f - 2.0f * xy.y / float(u_image.y));
  return vec3(ndc.x * u_tan_half.x, ndc.y * u_tan_half.y, 1.0f);
}

// Image position in pixels of view-space point v (view_ray_at's inverse).
vec2 image_position(vec3 v) {
  return vec2((v.x / (v.z * u_tan_half.x) + 1.0f) * 0.5f * float(u_image.x),
              (1.0f - v.y / (v.z * u_tan_half.y)) * 0.5f * float(u_image.y));
}

vec3 view_to_world_direction(vec3 v) { return v.x * u_right + v.y * u_up + v.z * u_forward; }
vec3 world_to_view_direction(vec3 w) { return vec3(dot(w, u_right), dot(w, u_up), dot(w, u_forward)); }

float point_depth(SurfacePoint v) {
  vec2 d = sd_depths(v.span);
  return v.end == 0u ? d.x : d.y;
}

vec3 point_position(SurfacePoint v) { return view_ray_at(vec2(v.pixel) + vec2(0.5f)) * point_depth(v); }

// Whether v's link towards dir was cut at a fold (render/model/links.glsl).
bool folds_away(SurfacePoint v, int dir) { return link_byte(link_word(v), dir) == VX_LINK_FOLD; }

struct SobelSample {
  vec3 position;       // view space
  SurfacePoint point;  // the linked point
  bool across;         // in the neighbour pixel; false: a wall sample in v's own column
  bool folded;         // not across: the link was cut at a fold
};

SobelSample sobel_step(SurfacePoint v, int dir) {
  SobelSample s;
  s.point = follow_link(v, dir);
  s.across = link_is_across(v, dir);
  s.folded = !s.across && folds_away(v, dir);
  if (s.across) {
    s.position = point_position(s.point);
  } else {
    vec2 xy = vec2(v.pixel) + vec2(0.5f) + 0.5f * vec2(link_step(dir));
    float z = s.folded ? point_depth(v) : 0.5f * (point_depth(v) + point_depth(s.point));
    s.position = view_ray_at(xy) * z;
  }
  return s;
}

// Corner sample: horizontal step h, then vertical direction dir_y.
vec3 sobel_corner(SobelSample h, int dir_y) { return h.across ? sobel_step(h.point, dir_y).position : h.position; }

// Whether the surface at v goes on to the walls towards dir rather than turning there. The
// fluid's spans are cut where its walls begin (render/backdrop.h): a neighbour whose walls
// stand in front of v has lost its fluid to them, and v's link towards it ends although the
// surface goes on behind the wall. And where v's own span ends on its walls, the water reaches
// them: a neighbour that meets walls and no water lies past the line where the surface meets
// a wall (water against the back wall, seen from the front), not past a silhouette.
bool hidden_by_walls(SurfacePoint v, int dir) {
  ivec2 q = v.pixel + link_step(dir);
  if (!in_image(q)) return false;
  float wall = sd_wall_depth(q);
  if (wall <= point_depth(v)) return true;
  return wall < 3.0e38f && sd_raw_depths(v.span).y >= sd_wall_depth(v.pixel);
}

// Whether the side of v towards dir, whose Sobel sample is s, is hidden: by walls or behind a fold.
bool hidden_side(SurfacePoint v, SobelSample s, int dir) {
  return s.folded || (!s.across && hidden_by_walls(v, dir));
}

// A Sobel tangent (towards +x or row + 1) from its halves before and after the point, and
// whether a wall hides each side.
vec3 sobel_tangent(vec3 before, vec3 after, bool hidden_before, bool hidden_after) {
  if (hidden_before && !hidden_after) return 2.0f * after;
  if (hidden_after && !hidden_before) return 2.0f * before;
  return before + after;
}

// Outward unit normal at v, view space.
vec3 sobel_normal_view(SurfacePoint v) {
  vec3 c = point_position(v);
  SobelSample l = sobel_step(v, 0);
  SobelSample r = sobel_step(v, 1);
  SobelSample u = sobel_step(v, 2);
  SobelSample d = sobel_step(v, 3);
  vec3 lu = sobel_corner(l, 2);
  vec3 ld = sobel_corner(l, 3);
  vec3 ru = sobel_corner(r, 2);
  vec3 rd = sobel_corner(r, 3);
  // Where a wall or a fold hides one side, the tangent is the other side's half alone (a
  // one-sided difference), and the other tangent leaves that side's row or column out: a
  // silhouette's wall sample there would turn the surface edge-on along every wall the water
  // touches, a line of grazing normals that reflect the sky in translucent water and bend
  // refracted rays aside (dots where the water meets a wall), and a corner reached past the
  // hidden side through a neighbour's own link may lie on the other sheet of a fold.
  // In units of v's depth: the cross product of world lengths is an area, whose squares under-
  // or overflow floats at scene scales past 1e-7 or 1e11 world units; relative to the depth
  // the numbers are the same at every scale.
  float unit = 1.0f / c.z;
  bool hl = hidden_side(v, l, 0);
  bool hr = hidden_side(v, r, 1);
  bool hu = hidden_side(v, u, 2);
  bool hd = hidden_side(v, d, 3);
  float wu = hu && !hd ? 0.0f : 1.0f;
  float wd = hd && !hu ? 0.0f : 1.0f;
  float wl = hl && !hr ? 0.0f : 1.0f;
  float wr = hr && !hl ? 0.0f : 1.0f;
  vec3 tx = sobel_tangent((wu * (u.position - lu) + 2.0f * (c - l.position) + wd * (d.position - ld)) * unit,
                          (wu * (ru - u.position) + 2.0f * (r.position - c) + wd * (rd - d.position)) * unit,
                          hl, hr);
  vec3 ty = sobel_tangent((wl * (l.position - lu) + 2.0f * (c - u.position) + wr * (r.position - ru)) * unit,
                          (wl * (ld - l.position) + 2.0f * (d.position - c) + wr * (rd - r.position)) * unit,
                          hu, hd);
  vec3 n = cross(tx, ty);
  float len = length(n);
  // Out of the fluid: towards the eye at an entry, away from it at an exit.
  float facing = v.end == 0u ? -1.0f : 1.0f;
  if (!(len > 1e-30f)) return facing * normalize(c);
  n = n / len;
  return dot(n, c) * facing >= 0.0f ? n : -n;
}

// Whether v lies on a crest: a link cut at a fold, or one that steps more than
// VX_CREST_STEP_SHARE fold steps in depth (2 particle spacings in the views). At a wave's crest
// the rays that graze its lip meet either a particle's cap on the lip or the crest's back just
// behind it, from pixel to pixel along the crest: the lip is beaded at the particle scale, finer
// than a pixel. The Sobel normal takes each such step for a slope, so along the crest grazing
// normals (bright: the sky's reflection) alternate with the caps' (dark): a dotted line.
#define VX_CREST_STEP_SHARE 0.8f
bool on_crest(SurfacePoint v) {
  if (!(u_fold_step > 0.0f)) return false;
  float z = point_depth(v);
  for (int dir = 0; dir < 4; ++dir) {
    uint b = link_byte(link_word(v), dir);
    if (b == VX_LINK_FOLD) return true;
    if (b <= VX_LINK_MAX_INDEX &&
        abs(point_depth(follow_link(v, dir)) - z) > VX_CREST_STEP_SHARE * u_fold_step)
      return true;
  }
  return false;
}

// The encoded world-space Sobel normals (entry, exit) of span `span` of pixel p: the normals
// pass's first dispatch.
uvec2 span_normal_words(ivec2 p, uint span) {
  vec3 in_normal = view_to_world_direction(sobel_normal_view(surface_point(p, span, 0u)));
  vec3 out_normal = view_to_world_direction(sobel_normal_view(surface_point(p, span, 1u)));
  return uvec2(encode_normal(in_normal), encode_normal(out_normal));
}

// The encoded normal of a crest point v (on_crest; the normals pass's second dispatch, which
// writes these over the first's): on a crest the step between pixels is below the picture's
// resolution, and the mean of the stored Sobel normals of v's linked neighbours off the crest
// stands for it (v's own where none is). It reads only points off the crest, and the dispatch
// writes only points on it, so the normals are rewritten in place.
uint crest_normal_word(SurfacePoint v) {
  vec3 sum = vec3(0.0f);
  for (int dir = 0; dir < 4; ++dir) {
    if (!link_is_across(v, dir)) continue;
    SurfacePoint w = follow_link(v, dir);
    if (on_crest(w)) continue;
    sum += decode_normal(sd_normal_word(w.span, w.end));
  }
  if (!(length(sum) > 1e-30f)) return sd_normal_word(v.span, v.end);
  return encode_normal(normalize(sum));
}

#endif
