// render/span_image.glsl - the span image on the GPU (render/span_image.h has the full
// contract): per pixel p = x + y * width a PixelSpans record, and its spans
// span_depths[offset .. offset + count) as vec2(entry, exit) view depths in world units.
// `inside` is the fluid length along the ray (world units), exact past a span cap.
// Before including, a pass may define SPAN_PIXELS_BINDING / SPAN_DEPTHS_BINDING (default 0, 1)
// and SPAN_IMAGE_ACCESS (default: read and write; e.g. `readonly`).

#include "render/perspective_grid.glsl"

#ifndef SPAN_PIXELS_BINDING
#define SPAN_PIXELS_BINDING 0
#endif
#ifndef SPAN_DEPTHS_BINDING
#define SPAN_DEPTHS_BINDING 1
#endif
#ifndef SPAN_IMAGE_ACCESS
#define SPAN_IMAGE_ACCESS
#endif

struct PixelSpans {
  uint offset;   // first span in span_depths
  uint count;    // spans stored
  uint total;    // spans found; total > count: the last stored span was extended (capped)
  float inside;  // fluid length along the ray, world units
};

layout(std430, binding = SPAN_PIXELS_BINDING) SPAN_IMAGE_ACCESS buffer SpanPixels {
  PixelSpans span_pixels[];
};
layout(std430, binding = SPAN_DEPTHS_BINDING) SPAN_IMAGE_ACCESS buffer SpanDepths {
  vec2 span_depths[];
};

uint span_pixel_index(ivec2 pixel) { return uint(pixel.x) + uint(pixel.y) * uint(u_image.x); }
