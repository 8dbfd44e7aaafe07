#include "render/span_image.h"

namespace voxspan {

std::int64_t SpanImage::capped_pixels() const {
  std::int64_t n = 0;
  for (const PixelSpans& p : pixels) n += p.total > p.count;
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
  inside_ += (exit - entry) * ray_scale;
  if (cap_ == 0 || found_ < cap_) out_.push_back({float(entry), float(exit)});
  else out_.back().exit = float(exit);  // sec. 3.1: extend the last stored span
  ++found_;
}

PixelSpans SpanListBuilder::end() const {
  return {first_, static_cast<std::uint32_t>(out_.size()) - first_, found_, float(inside_)};
}

}  // namespace voxspan
