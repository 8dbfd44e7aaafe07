#include "render/gl/gpu_span_image.h"

#include <algorithm>

#include "render/gl/bindings.h"
#include "voxspan/error.h"

namespace voxspan {

void GpuSpanImage::bind() const {
  pixels_.bind(GL_SHADER_STORAGE_BUFFER, binding::kSpanPixels);
  spans_.bind(GL_SHADER_STORAGE_BUFFER, binding::kSpanDepths);
}

SpanImage GpuSpanImage::download() const {
  SpanImage image;
  download(image);
  return image;
}

void GpuSpanImage::download(SpanImage& out) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  out.grid = grid_;
  pixels_.read(out.pixels, static_cast<std::size_t>(width()) * height());
  spans_.read(out.spans, span_count_);
}

void GpuSpanImage::upload(const SpanImage& image) {
  grid_ = image.grid;
  const std::size_t pixels = static_cast<std::size_t>(width()) * height();
  if (image.pixels.size() != pixels)
    throw make_error("GpuSpanImage::upload: ", image.pixels.size(), " pixel records for a ",
                     width(), "x", height(), " grid");
  pixels_.reserve(std::max<std::size_t>(16, pixels * sizeof(PixelSpans)));
  if (pixels != 0) pixels_.upload(image.pixels.data(), pixels * sizeof(PixelSpans));
  spans_.reserve(std::max<std::size_t>(sizeof(Span) * 1024, image.spans.size() * sizeof(Span)));
  if (!image.spans.empty()) spans_.upload(image.spans.data(), image.spans.size() * sizeof(Span));
  span_count_ = image.spans.size();
}

std::size_t GpuSpanImage::reset(const PerspectiveGrid& grid) {
  grid_ = grid;
  span_count_ = 0;
  const std::size_t bytes = static_cast<std::size_t>(width()) * height() * sizeof(PixelSpans);
  pixels_.reserve(bytes);
  if (spans_.id() == 0) spans_ = gl::Buffer(sizeof(Span) * 1024);
  return bytes;
}

void GpuSpanImage::reserve_spans(std::size_t spans, std::size_t max_binding_bytes) {
  const std::size_t bytes = spans * sizeof(Span);
  if (bytes <= spans_.size()) return;
  if (bytes > max_binding_bytes)
    throw make_error("the span image needs ", spans, " spans (", bytes,
                     " bytes), more than one GL binding holds (", max_binding_bytes,
                     "); set a span cap (max_spans) or coarsen the view");
  // Grow by half again so a slowly more complex scene does not copy every step.
  gl::Buffer grown(std::min(max_binding_bytes, std::max(bytes, spans_.size() + spans_.size() / 2)));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // spans written by shaders are copied
  grown.copy_from(spans_, span_count_ * sizeof(Span));
  spans_ = std::move(grown);
}

}  // namespace voxspan
