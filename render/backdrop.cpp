#include "render/backdrop.h"

#include <algorithm>

#include "voxspan/error.h"

namespace voxspan {

std::int64_t clip_at_walls(const SpanImage& spans, const Backdrop& backdrop, SpanImage& out) {
  const int width = spans.width(), height = spans.height();
  if (backdrop.width != width || backdrop.height != height)
    throw make_error("the backdrop is ", backdrop.width, "x", backdrop.height, ", the span image ",
                     width, "x", height);
  out.grid = spans.grid;
  out.pixels.resize(spans.pixels.size());
  out.spans.clear();
  std::int64_t cut = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelSpans& in = spans.pixel(x, y);
      PixelSpans& p = out.pixels[std::size_t(x) + std::size_t(y) * std::size_t(width)];
      p = in;
      p.offset = static_cast<std::uint32_t>(out.spans.size());
      const float wall = backdrop.wall_depth(x, y);
      const std::span<const Span> list = spans.spans_at(x, y);
      if (list.empty() || list.back().exit <= wall) {
        out.spans.insert(out.spans.end(), list.begin(), list.end());
        continue;
      }
      ++cut;
      double length = 0;
      for (const Span& s : list) {
        if (s.entry >= wall) break;
        out.spans.push_back({s.entry, std::min(s.exit, wall)});
        length += out.spans.back().exit - s.entry;
      }
      p.count = p.total = static_cast<std::uint32_t>(out.spans.size() - p.offset);
      p.inside = static_cast<float>(length * spans.grid.view().ray_scale(x, y));
    }
  return cut;
}

}  // namespace voxspan
