// Reads the span image the way later passes will (render/gl/span_image.glsl): per pixel, the
// capped gap length and the sum of the stored span lengths along the ray.
layout(local_size_x = 64) in;

#define SPAN_IMAGE_ACCESS readonly
#include "render/gl/span_image.glsl"

layout(std430, binding = 2) writeonly buffer Out { vec2 probe[]; };

void main() {
  uint p = gl_GlobalInvocationID.x;
  if (p >= uint(u_image.x * u_image.y)) return;
  ivec2 pixel = ivec2(p % uint(u_image.x), p / uint(u_image.x));
  PixelSpans s = span_pixels[p];
  float stored = 0.0;
  for (uint k = 0u; k < s.count; ++k) stored += span_depths[s.offset + k].y - span_depths[s.offset + k].x;
  probe[p] = vec2(span_capped_gap_length(pixel), stored * ray_scale(pixel));
}
