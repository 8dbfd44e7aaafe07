// render/gl/gpu_span_image.h - the span image (render/span_image.h) as it lives on the GPU, where
// the voxelization leaves it and the later passes (connect, filter, normals, shading) read it.
//   pixels(): width * height PixelSpans, std430 {uint offset; uint count; uint total; float
//             inside;}, pixel p = x + y * width, row 0 at the top;
//   spans():  Span = vec2(entry, exit) view depths, span_count() of them in use.
// render/gl/span_image.glsl declares the same buffers for shaders; bind() puts them at the
// bindings render/gl/bindings.h reserves.
#pragma once

#include <cstddef>

#include "render/gl/objects.h"
#include "render/perspective_grid.h"
#include "render/span_image.h"

namespace voxspan {

class GpuSpanImage {
 public:
  const PerspectiveGrid& grid() const { return grid_; }
  int width() const { return grid_.width(); }
  int height() const { return grid_.height(); }
  const gl::Buffer& pixels() const { return pixels_; }
  const gl::Buffer& spans() const { return spans_; }
  std::size_t span_count() const { return span_count_; }

  void bind() const;
  // Reads the whole image back (tests, the CPU paths, file output).
  SpanImage download() const;
  // The same into `out`, keeping its memory (a read-back every frame).
  void download(SpanImage& out) const;
  // Replaces the image with one made on the CPU (a composited or hand-made span image, or the
  // exact reference), for the passes after the voxelization.
  void upload(const SpanImage& image);

  // For the voxelizer: starts a frame in `grid`, no spans, the pixel records sized (their bytes
  // returned) for the voxelizer to clear.
  std::size_t reset(const PerspectiveGrid& grid);
  // Grows the span buffer to hold `spans`, keeping the spans already written.
  void reserve_spans(std::size_t spans, std::size_t max_binding_bytes);
  void set_span_count(std::size_t spans) { span_count_ = spans; }
  gl::Buffer& pixels() { return pixels_; }

 private:
  PerspectiveGrid grid_;
  gl::Buffer pixels_;
  gl::Buffer spans_;
  std::size_t span_count_ = 0;
};

}  // namespace voxspan
