// Crest normals (render/gl/passes/normals.h), the normals pass's second dispatch: one thread per
// span rewrites the stored normal of each end on a crest from its neighbours' off the crest
// (render/model/surface_geometry.glsl's crest_normal_word). Only ends on a crest are written and
// only ends off it are read, so the normals are rewritten in place.
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
  ivec2 p = owner_pixel(s);
  SurfacePoint entry = surface_point(p, s, 0u);
  SurfacePoint exit = surface_point(p, s, 1u);
  if (on_crest(entry)) span_normals[s].x = crest_normal_word(entry);
  if (on_crest(exit)) span_normals[s].y = crest_normal_word(exit);
}
