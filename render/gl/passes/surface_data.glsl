// render/gl/passes/surface_data.glsl - the per-span surface data the passes after the voxelization
// keep beside the span image (render/gl/gpu_surfaces.h), and the sd_* accessors through which the
// shared model files (render/model/*.glsl) read it, after the span image (render/gl/span_image.glsl)
// at the bindings render/gl/bindings.h reserves (binding::surface_defines()):
//   span_owner[span]     pixel index x + y * width of each span
//   span_links[span]     (entry word, exit word), render/model/links.glsl
//   surface_depths[span] (entry, exit) after the filter (the span depths when it is off)
//   span_normals[span]   (entry, exit) octahedral words, render/model/octahedral.glsl
//   pixel_ao[pixel]      deep ambient occlusion of the front surface
//   wall_pixels[pixel]   the backdrop (render/backdrop.h), whose depths sd_wall_depth reads where
//                        u_walls_cut is set (the normals pass: render/gl/passes/normals.h)
// and u_fold_step, the depth step at which links.glsl sees a fold (set by the connect pass, and
// by the normals pass, where it marks crests).
// Include after render/gl/span_image.glsl.

layout(std430, binding = SPAN_OWNERS_BINDING) buffer SpanOwners { uint span_owner[]; };
layout(std430, binding = SPAN_LINKS_BINDING) buffer SpanLinks { uvec2 span_links[]; };
layout(std430, binding = SURFACE_DEPTHS_BINDING) buffer SurfaceDepths { vec2 surface_depths[]; };
layout(std430, binding = SPAN_NORMALS_BINDING) buffer SpanNormals { uvec2 span_normals[]; };
layout(std430, binding = PIXEL_AO_BINDING) buffer PixelAo { float pixel_ao[]; };
layout(std430, binding = WALL_DEPTHS_BINDING) readonly buffer WallPixels { vec4 wall_pixels[]; };
uniform int u_walls_cut;  // 0 (the default): no walls
uniform float u_fold_step;  // render/model/links.glsl's; 0: no folds

uint sd_count(ivec2 p) { return span_pixels[span_pixel_index(p)].count; }
uint sd_offset(ivec2 p) { return span_pixels[span_pixel_index(p)].offset; }
float sd_inside(ivec2 p) { return span_pixels[span_pixel_index(p)].inside; }
vec2 sd_raw_depths(uint span) { return span_depths[span]; }
vec2 sd_depths(uint span) { return surface_depths[span]; }
uvec2 sd_links(uint span) { return span_links[span]; }
uvec2 sd_normals(uint span) { return span_normals[span]; }
uint sd_normal_word(uint span, uint end) { return span_normals[span][end]; }
float sd_ao(ivec2 p) { return pixel_ao[span_pixel_index(p)]; }
float sd_wall_depth(ivec2 p) { return u_walls_cut != 0 ? wall_pixels[span_pixel_index(p)].w : 3.0e38; }

ivec2 owner_pixel(uint span) {
  uint i = span_owner[span];
  return ivec2(int(i % uint(u_image.x)), int(i / uint(u_image.x)));
}
