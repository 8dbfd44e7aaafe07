// render/span_image.h - the span image: what the voxelization hands to every later stage
// ([ZD15] sec. 3.1-3.2). Per pixel an ordered list of spans, each the (entry, exit) depth of
// one stretch of fluid along the pixel's ray, and the exact total length of fluid on the ray.
//
// Units and convention (render/perspective_grid.h): depths are view-space z in world units;
// lengths are along the ray in world units (a depth interval dz is dz * ray_scale(x, y) long).
//
// Storage is variable length: pixel p = x + y * width (row 0 at the top) owns
// spans[offset, offset + count). When more spans than the cap were found (total > count), the
// last stored span was extended to the exit of the last one found, and the empty space inside
// it is excluded from `inside`, so that absorption stays exact (sec. 3.1).
//
// The same layout lives on the GPU (render/gl/gpu_span_image.h, render/gl/span_image.glsl): a
// buffer of PixelSpans (std430, 16 bytes each) and a buffer of Span (vec2, 8 bytes each).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/perspective_grid.h"

namespace voxspan {

struct Span {
  float entry = 0;  // view depth where the ray enters the fluid
  float exit = 0;   // view depth where it leaves; entry < exit
};
static_assert(sizeof(Span) == 8);

struct PixelSpans {
  std::uint32_t offset = 0;  // first span in SpanImage::spans
  std::uint32_t count = 0;   // spans stored (<= the cap when one is set)
  std::uint32_t total = 0;   // spans found before the cap; total > count means capped
  float inside = 0;          // length of fluid along the ray (world units), all spans counted
  bool capped() const { return total > count; }
};
static_assert(sizeof(PixelSpans) == 16);

struct SpanImage {
  PerspectiveGrid grid;            // the frame the spans live in (camera, near, layers)
  std::vector<PixelSpans> pixels;  // width * height
  std::vector<Span> spans;

  int width() const { return grid.width(); }
  int height() const { return grid.height(); }
  const PixelSpans& pixel(int x, int y) const {
    return pixels[static_cast<std::size_t>(x) + static_cast<std::size_t>(y) * width()];
  }
  std::span<const Span> spans_at(int x, int y) const {
    const PixelSpans& p = pixel(x, y);
    return {spans.data() + p.offset, p.count};
  }
  // Empty length (along the ray, world units) inside the pixel's extended last span: the gaps
  // between the spans folded into it past the cap (sec. 3.1); 0 for pixels not capped.
  // Derived as stored span lengths minus `inside`, clamped at 0 against float rounding.
  double capped_gap_length(int x, int y) const;
  // Pixels whose spans were capped, and all spans found (stored or not).
  std::int64_t capped_pixels() const;
  std::int64_t total_spans() const;
  // The sum of `inside` over the image (world units).
  double inside_sum() const;
};

// The per-pixel list rule shared by the GPU's compress pass and the exact reference: spans
// arrive in depth order; the first cap - 1 are stored as found, the cap-th is extended to the
// exit of the last one. cap = 0 stores every span.
class SpanListBuilder {
 public:
  SpanListBuilder(std::vector<Span>& out, std::uint32_t cap) : out_(out), cap_(cap) {}
  void begin() { first_ = static_cast<std::uint32_t>(out_.size()), found_ = 0, inside_ = 0; }
  void add(double entry, double exit, double ray_scale);
  PixelSpans end() const;

 private:
  std::vector<Span>& out_;
  std::uint32_t cap_;
  std::uint32_t first_ = 0, found_ = 0;
  double inside_ = 0;
};

}  // namespace voxspan
