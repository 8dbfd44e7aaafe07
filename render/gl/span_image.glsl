// render/gl/span_image.glsl - the span image on the GPU (render/span_image.h has the full
// contract): per pixel p = x + y * width a PixelSpans record, and its spans
// span_depths[offset .. offset + count) as vec2(entry, exit) view depths in world units.
// `inside` is the fluid length along the ray (world units), exact past a span cap.
// The pass hands the bindings in (binding::span_image_defines(), render/gl/bindings.h); before
// including, it may define SPAN_IMAGE_ACCESS (default: read and write; e.g. `readonly`).

#include "render/gl/perspective_grid.glsl"

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

// Empty length (along the ray, world units) inside the extended last span of a capped pixel
// (sec. 3.1): stored span lengths minus `inside`; 0 when the pixel was not capped.
float span_capped_gap_length(ivec2 pixel) {
  PixelSpans p = span_pixels[span_pixel_index(pixel)];
  if (p.total <= p.count) return 0.0;
  float stored = 0.0;
  for (uint k = 0u; k < p.count; ++k)
    stored += span_depths[p.offset + k].y - span_depths[p.offset + k].x;
  return max(0.0, stored * ray_scale(pixel) - p.inside);
}
