// One pass of the surface filter ([ZD15] sec. 3.4, 4.6; render/gl/passes/filter.h): one thread per
// span, the rule in render/model/surface_filter.glsl, from surface_depths (the previous pass's)
// into filtered_depths.
layout(local_size_x = 64) in;

#define SPAN_IMAGE_ACCESS readonly
#include "render/gl/span_image.glsl"
#include "render/gl/passes/surface_data.glsl"
#include "render/gl/passes/thread_index.glsl"
#include "render/model/links.glsl"
#include "render/model/octahedral.glsl"
#include "render/model/surface_geometry.glsl"

layout(std430, binding = FILTERED_DEPTHS_BINDING) writeonly buffer FilteredDepths {
  vec2 filtered_depths[];
};

uniform uint u_filter_pass;       // 0 .. 3
uniform uint u_max_iterations;
uniform float u_radius;           // world units
uniform float u_iteration_scale;  // n(z) = ceil(u_iteration_scale / z^2)

#include "render/model/surface_filter.glsl"

void main() {
  uint s = thread_index();
  if (s >= u_thread_count) return;
  filtered_depths[s] = filter_span(owner_pixel(s), s);
}
