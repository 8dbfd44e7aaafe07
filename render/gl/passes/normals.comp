// Surface normals ([ZD15] sec. 3.4, 4.5; render/gl/passes/normals.h), the first dispatch: one
// thread per span builds the Sobel normal of its entry and its exit along the links on the
// surface depths (render/model/surface_geometry.glsl) and stores both octahedral-encoded. Crest
// points are left to the second (crest_normals.comp): computing their neighbours' normals here
// held a whole SIMD group up for each crest point in it.
layout(local_size_x = 64) in;

#define SPAN_IMAGE_ACCESS readonly
#include "render/gl/span_image.glsl"
#include "render/gl/passes/surface_data.glsl"
#include "render/gl/passes/thread_index.glsl"
#include "render/model/links.glsl"
#include "render/model/octahedral.glsl"
#include "render/model/surface_geometry.glsl"

void main() {
  uint s = thread_index();
  if (s >= u_thread_count) return;
  span_normals[s] = span_normal_words(owner_pixel(s), s);
}
