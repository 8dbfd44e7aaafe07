// Deep ambient occlusion ([ZD15] sec. 3.6; render/gl/passes/deep_ao.h): one thread per pixel
// samples the spans of u_ao_samples neighbouring columns, all layers, around its front surface
// point (render/model/deep_ao.glsl).
layout(local_size_x = 64) in;

#define SPAN_IMAGE_ACCESS readonly
#include "render/gl/span_image.glsl"
#include "render/gl/passes/surface_data.glsl"
#include "render/gl/passes/thread_index.glsl"
#include "render/gl/passes/shade_uniforms.glsl"
#include "render/model/links.glsl"
#include "render/model/octahedral.glsl"
#include "render/model/surface_geometry.glsl"
#include "render/model/deep_ao.glsl"

void main() {
  uint i = thread_index();
  if (i >= u_thread_count) return;
  pixel_ao[i] = deep_ao(ivec2(int(i % uint(u_image.x)), int(i / uint(u_image.x))));
}
