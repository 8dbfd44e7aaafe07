// render/model/links.glsl - surface links between the spans of neighbouring pixels ([ZD15], sec.
// 3.3 and Listing 1), shared by the GPU passes and the C++ host (render/model/host.h: the CPU
// renderer and the reference).
//
// Each span has two surface points, its entry (end 0) and its exit (end 1), and each point one
// 32-bit link word (sec. 4.5): one byte per direction, byte d for direction d = 0 left (-x),
// 1 right (+x), 2 up (row - 1), 3 down (row + 1). A byte is
//   0..252   the linked point is span (byte) of the neighbour pixel, counted from that pixel's
//            first span, and the same end (an entry links an entry, an exit an exit);
//   253 FOLD an entry whose link there would cross a fold (link_crosses_fold): the surface goes
//            on out of sight; followed, it reads as SELF;
//   254 SELF the span overlaps nothing there: its entry and exit link each other (Fig. 3c);
//   255 OWN  a bubble wall: an entry links the previous exit of its own column, an exit the
//            next entry (Fig. 3b).
// A neighbour span index past 252 cannot be stored; such a link reads as SELF (the surface
// ends there), which only columns with more than 253 stored spans can meet.
//
// Host needs: uint sd_count(ivec2), uint sd_offset(ivec2), vec2 sd_raw_depths(uint) (the span
// image's (entry, exit)), uvec2 sd_links(uint) (entry word, exit word), ivec2 u_image, float
// u_fold_step (the connect pass's: view depth; 0, no folds).
#ifndef VX_MODEL_LINKS
#define VX_MODEL_LINKS

#define VX_LINK_MAX_INDEX 252u
#define VX_LINK_FOLD 253u
#define VX_LINK_SELF 254u
#define VX_LINK_OWN 255u

ivec2 link_step(int dir) {
  if (dir == 0) return ivec2(-1, 0);
  if (dir == 1) return ivec2(1, 0);
  if (dir == 2) return ivec2(0, -1);
  return ivec2(0, 1);
}

bool in_image(ivec2 p) { return p.x >= 0 && p.y >= 0 && p.x < u_image.x && p.y < u_image.y; }

uint link_byte(uint word, int dir) { return (word >> uint(8 * dir)) & 255u; }

// First span j of pixel q whose exit >= z (binary search, exits increase); the count if none.
uint first_span_exiting_after(ivec2 q, float z) {
  uint lo = 0u, hi = sd_count(q);
  uint base = sd_offset(q);
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (sd_raw_depths(base + mid).y >= z) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

// Number of spans of pixel q whose entry <= z (entries increase).
uint spans_entering_before(ivec2 q, float z) {
  uint lo = 0u, hi = sd_count(q);
  uint base = sd_offset(q);
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (sd_raw_depths(base + mid).x <= z) lo = mid + 1u; else hi = mid;
  }
  return lo;
}

uint link_index_byte(uint j) { return j <= VX_LINK_MAX_INDEX ? j : VX_LINK_SELF; }

// Whether the link from the entry of span s towards the entry of span t of the neighbour pixel
// crosses a fold: a depth step longer than u_fold_step. Listing 1 links the spans of
// neighbouring pixels wherever they overlap, which also holds where a wave's crest hides the
// water behind it: the ray under the crest goes on through the crest into that water, on one
// span, and the neighbour's ray, over the crest, meets the water behind several particle
// spacings further on. Linked, the filter averaged the two sheets' depths and the normals took
// the step for a slope, turning both rows towards grazing; and which pixels along the crest
// hold a sliver of its tip (a span of its own, not linked across) changes from pixel to pixel:
// a dotted line along the crest. Cut there, each sheet is filtered and shaded on its own side.
// Entries only: exits, the water's far side, are seen only through it (in a first version,
// cutting them too moved the 30 000-particle dam break's speckle counts by 3 or fewer).
bool link_crosses_fold(uint s, uint t) {
  return u_fold_step > 0.0f && abs(sd_raw_depths(t).x - sd_raw_depths(s).x) > u_fold_step;
}

// Listing 1 for span k (0-based within pixel p) towards direction dir: the (entry, exit) bytes.
uvec2 connect_direction(ivec2 p, uint k, int dir) {
  ivec2 q = p + link_step(dir);
  if (!in_image(q)) return uvec2(VX_LINK_SELF);
  uint base = sd_offset(p);
  uint n = sd_count(p);
  vec2 cur = sd_raw_depths(base + k);
  uint qbase = sd_offset(q);
  uint m = sd_count(q);
  uint front = first_span_exiting_after(q, cur.x);
  if (front >= m) return uvec2(VX_LINK_SELF);
  vec2 front_nb = sd_raw_depths(qbase + front);
  if (!(front_nb.x <= cur.y)) return uvec2(VX_LINK_SELF);
  uvec2 bytes;
  // Neighbour not connected to the previous span: link entries; else it is a bubble wall.
  if (k == 0u || front_nb.x > sd_raw_depths(base + k - 1u).y)
    bytes.x = link_crosses_fold(base + k, qbase + front) ? VX_LINK_FOLD : link_index_byte(front);
  else bytes.x = VX_LINK_OWN;
  // front_nb.entry <= cur.exit, so back >= front.
  uint back = spans_entering_before(q, cur.y) - 1u;
  vec2 back_nb = sd_raw_depths(qbase + back);
  // Neighbour not connected to the next span: link exits; else it recurs there (bubble wall).
  if (k + 1u >= n || sd_raw_depths(base + k + 1u).x > back_nb.y) bytes.y = link_index_byte(back);
  else bytes.y = VX_LINK_OWN;
  return bytes;
}

// The (entry word, exit word) of span k of pixel p.
uvec2 connect_span(ivec2 p, uint k) {
  uvec2 words = uvec2(0u);
  for (int dir = 0; dir < 4; ++dir) {
    uvec2 b = connect_direction(p, k, dir);
    words.x |= b.x << uint(8 * dir);
    words.y |= b.y << uint(8 * dir);
  }
  return words;
}

// A surface point: the entry (end 0) or exit (end 1) of span `span` (index into the span
// array) of pixel `pixel`.
struct SurfacePoint {
  ivec2 pixel;
  uint span;
  uint end;
};

SurfacePoint surface_point(ivec2 pixel, uint span, uint end) {
  SurfacePoint v;
  v.pixel = pixel;
  v.span = span;
  v.end = end;
  return v;
}

uint link_word(SurfacePoint v) {
  uvec2 words = sd_links(v.span);
  return v.end == 0u ? words.x : words.y;
}

// Whether v's link towards dir reaches the neighbour pixel (bytes 0..252).
bool link_is_across(SurfacePoint v, int dir) { return link_byte(link_word(v), dir) <= VX_LINK_MAX_INDEX; }

// The point v's link towards dir names: in the neighbour pixel, or, for SELF, FOLD and OWN, in
// v's own column (the other end of its span, or the adjacent end of the adjacent span).
SurfacePoint follow_link(SurfacePoint v, int dir) {
  uint b = link_byte(link_word(v), dir);
  if (b <= VX_LINK_MAX_INDEX) {
    ivec2 q = v.pixel + link_step(dir);
    return surface_point(q, sd_offset(q) + b, v.end);
  }
  if (b == VX_LINK_SELF || b == VX_LINK_FOLD) return surface_point(v.pixel, v.span, 1u - v.end);
  return v.end == 0u ? surface_point(v.pixel, v.span - 1u, 1u) : surface_point(v.pixel, v.span + 1u, 0u);
}

#endif
