// The fluid's spans cut where the walls begin (render/gl/passes/cut_at_walls.h; the rule of
// render/backdrop.h's clip_at_walls): one thread per pixel, in place.
layout(local_size_x = 64) in;

#include "render/gl/span_image.glsl"
#include "render/gl/passes/thread_index.glsl"

layout(std430, binding = BACKDROP_BINDING) readonly buffer Backdrop { vec4 backdrop[]; };

void main() {
  uint p = thread_index();
  if (p >= u_thread_count) return;
  PixelSpans s = span_pixels[p];
  float wall = backdrop[p].w;
  if (s.count == 0u || span_depths[s.offset + s.count - 1u].y <= wall) return;
  uint kept = 0u;
  float length = 0.0;
  for (; kept < s.count; ++kept) {
    vec2 span = span_depths[s.offset + kept];
    if (span.x >= wall) break;
    span.y = min(span.y, wall);
    span_depths[s.offset + kept] = span;
    length += span.y - span.x;
  }
  ivec2 pixel = ivec2(int(p % uint(u_image.x)), int(p / uint(u_image.x)));
  s.count = kept;
  s.total = kept;
  s.inside = length * ray_scale(pixel);
  span_pixels[p] = s;
}
