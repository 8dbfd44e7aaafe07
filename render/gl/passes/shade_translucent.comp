// Translucent shading ([ZD15] sec. 3.5; render/gl/passes/shade_pixels.h): one thread per pixel,
// Fresnel reflection at the first entry and Beer-Lambert absorption over every span
// (render/model/shade_modes.glsl); one pass over the pixel's spans.
layout(local_size_x = 64) in;

#include "render/gl/passes/shade_common.glsl"

void main() {
  uint i = thread_index();
  if (i >= u_thread_count) return;
  shaded[i] = vec4(shade_translucent(thread_pixel(i)), 1.0);
}
