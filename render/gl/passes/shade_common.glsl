// render/gl/passes/shade_common.glsl - what every shading pass includes: the span image and the
// surface data (read only), the shading uniforms, the shared model files, and the output image
// (vec4 linear RGBA per pixel, row 0 at the top); bindings: binding::shade_defines().
#define SPAN_IMAGE_ACCESS readonly
#include "render/gl/span_image.glsl"
#include "render/gl/passes/surface_data.glsl"
#include "render/gl/passes/thread_index.glsl"
#include "render/gl/passes/shade_uniforms.glsl"
#include "render/model/links.glsl"
#include "render/model/octahedral.glsl"
#include "render/model/surface_geometry.glsl"
#include "render/model/environment.glsl"
#include "render/model/lighting.glsl"
// The walls behind the fluid, when u_use_backdrop (render/backdrop.h): rgb, a = view depth; the
// refractive pass's backdrop is followed by its pyramid (backdrop_pyramid).
layout(std430, binding = BACKDROP_BINDING) readonly buffer Backdrop { vec4 backdrop[]; };
vec4 sd_backdrop(ivec2 p) { return backdrop[p.x + p.y * u_image.x]; }
vec4 sd_backdrop_texel(uint i) { return backdrop[i]; }
// What lies behind a pixel: the backdrop, or the environment computed for every pixel of every
// frame (each thread reads its own).
vec3 sd_background(ivec2 p, vec3 dir) {
  return u_use_backdrop != 0 ? sd_backdrop(p).rgb : environment(u_eye, dir);
}
#include "render/model/shade_modes.glsl"

layout(std430, binding = SHADED_IMAGE_BINDING) writeonly buffer ShadedImage { vec4 shaded[]; };

ivec2 thread_pixel(uint i) { return ivec2(int(i % uint(u_image.x)), int(i / uint(u_image.x))); }
