// Opaque shading ([ZD15] sec. 3.5, "rendering the frontmost surface"; render/gl/passes/shade_pixels.h):
// one thread per pixel lights its first entry (render/model/shade_modes.glsl).
layout(local_size_x = 64) in;

#include "render/gl/passes/shade_common.glsl"

void main() {
  uint i = thread_index();
  if (i >= u_thread_count) return;
  shaded[i] = vec4(shade_opaque(thread_pixel(i)), 1.0);
}
