#include "render/span_image.h"

#include <algorithm>

namespace voxspan {

double SpanImage::capped_gap_length(int x, int y) const {
  const PixelSpans& p = pixel(x, y);
  if (p.total <= p.count) return 0;
  double stored = 0;
  for (const Span& s : spans_at(x, y)) stored += double(s.exit) - double(s.entry);
  return std::max(0.0, stored * grid.view().ray_scale(x, y) - double(p.inside));
}

std::int64_t SpanImage::capped_pixels() const {
  std::int64_t n = 0;
  for (const PixelSpans& p : pixels) n += p.capped();
  return n;
}

std::int64_t SpanImage::total_spans() const {
  std::int64_t n = 0;
  for (const PixelSpans& p : pixels) n += p.total;
  return n;
}

double SpanImage::inside_sum() const {
  double sum = 0;
  for (const PixelSpans& p : pixels) sum += p.inside;
  return sum;
}

void SpanListBuilder::add(double entry, double exit, double ray_scale) {
  // The length of the span as stored (in float): an MPI merge, which sees only the ranks' stored
  // spans, then sums the same lengths as one process does (insitu/parallel/span_merge.cpp).
  const float e = float(entry), x = float(exit);
  inside_ += (double(x) - double(e)) * ray_scale;
  if (cap_ == 0 || found_ < cap_) out_.push_back({e, x});
  else out_.back().exit = x;  // sec. 3.1: extend the last stored span
  ++found_;
}

PixelSpans SpanListBuilder::end() const {
  return {first_, static_cast<std::uint32_t>(out_.size()) - first_, found_, float(inside_)};
}

}  // namespace voxspan
