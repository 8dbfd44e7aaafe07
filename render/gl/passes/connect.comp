// Surface connection ([ZD15] sec. 3.3, Listing 1; render/gl/passes/connect.h).
// CONNECT_OWNERS: one thread per pixel writes its pixel number beside each of its spans and
// tallies the spans past index 252, which links cannot name. Otherwise one thread per span
// links its entry and exit to the overlapping spans of the four neighbour pixels
// (render/model/links.glsl): two binary searches per neighbour.
layout(local_size_x = 64) in;

#define SPAN_IMAGE_ACCESS readonly
#include "render/gl/span_image.glsl"
#include "render/gl/passes/surface_data.glsl"
#include "render/gl/passes/thread_index.glsl"
#include "render/model/links.glsl"

layout(std430, binding = TALLY_BINDING) buffer ConnectTally { uint unlinkable_spans; };

void main() {
  uint i = thread_index();
  if (i >= u_thread_count) return;
#ifdef CONNECT_OWNERS
  PixelSpans px = span_pixels[i];
  // At most layers / 2 spans per pixel: within llvmpipe's loop limit for 131072 layers.
  for (uint k = 0u; k < px.count; ++k) span_owner[px.offset + k] = i;
  if (px.count > VX_LINK_MAX_INDEX + 1u) atomicAdd(unlinkable_spans, px.count - VX_LINK_MAX_INDEX - 1u);
#else
  ivec2 p = owner_pixel(i);
  span_links[i] = connect_span(p, i - sd_offset(p));
#endif
}
