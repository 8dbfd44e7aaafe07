// First-hit distances (render/gl/passes/first_hit.h): one thread per pixel.
layout(local_size_x = 64) in;

#define SPAN_IMAGE_ACCESS readonly
#include "render/gl/span_image.glsl"
#include "render/gl/passes/thread_index.glsl"

layout(std430, binding = FIRST_HIT_BINDING) writeonly buffer FirstHit { vec4 first_hit[]; };
layout(std430, binding = DEPTHS_BINDING) readonly buffer Depths { vec2 depths[]; };

void main() {
  uint p = thread_index();
  if (p >= u_thread_count) return;
  ivec2 pixel = ivec2(int(p % uint(u_image.x)), int(p / uint(u_image.x)));
  PixelSpans s = span_pixels[p];
  float distance = s.count > 0u ? depths[s.offset].x * ray_scale(pixel) : 0.0;
  first_hit[p] = vec4(distance, 0.0, 0.0, 0.0);
}
