#include "render/backdrop.h"

#include <algorithm>
#include <span>

#include "voxspan/error.h"

namespace voxspan {

namespace {

void check_size(const SpanImage& spans, const Backdrop& backdrop) {
  if (backdrop.width != spans.width() || backdrop.height != spans.height())
    throw make_error("the backdrop is ", backdrop.width, "x", backdrop.height, ", the span image ",
                     spans.width(), "x", spans.height());
}

bool cut_by_walls(const PixelSpans& p, std::span<const Span> spans, float wall) {
  return p.count > 0 && spans[p.offset + p.count - 1].exit > wall;
}

}  // namespace

glm::vec4 over_backdrop(const Backdrop& backdrop, int x, int y, glm::vec3 c, float t,
                        bool background) {
  const glm::vec4 b =
      backdrop.pixels[std::size_t(x) + std::size_t(y) * std::size_t(backdrop.width)];
  if (!background && b.a == Backdrop::kNoWall) return glm::vec4(c, 1.0f - t);
  return glm::vec4(c + t * glm::vec3(b), 1.0f);
}

void backdrop_pyramid(const Backdrop& backdrop, std::vector<glm::vec4>& out) {
  out.assign(backdrop.pixels.begin(), backdrop.pixels.end());
  int w = backdrop.width, h = backdrop.height;
  std::size_t below = 0;  // where the level below starts in `out`
  for (int level = 1; level < kBackdropLevels; ++level) {
    const int nw = (w + 1) / 2, nh = (h + 1) / 2;
    const std::size_t start = out.size();
    out.resize(start + std::size_t(nw) * std::size_t(nh));
    for (int y = 0; y < nh; ++y)
      for (int x = 0; x < nw; ++x) {
        glm::vec4 sum(0.0f);
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            // Past the level's last row or column the edge texel stands in, as a clamped lookup.
            const int sx = std::min(2 * x + dx, w - 1), sy = std::min(2 * y + dy, h - 1);
            glm::vec4 t = out[below + std::size_t(sx) + std::size_t(sy) * std::size_t(w)];
            if (level == 1)
              t = t.a < Backdrop::kNoWall ? glm::vec4(glm::vec3(t), 1.0f) : glm::vec4(0.0f);
            sum += t;
          }
        out[start + std::size_t(x) + std::size_t(y) * std::size_t(nw)] = 0.25f * sum;
      }
    below = start;
    w = nw;
    h = nh;
  }
}

std::int64_t clip_at_walls(SpanImage& spans, const Backdrop& backdrop) {
  check_size(spans, backdrop);
  const int width = spans.width(), height = spans.height();
  std::int64_t cut = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      PixelSpans& p = spans.pixels[std::size_t(x) + std::size_t(y) * std::size_t(width)];
      const float wall = backdrop.wall_depth(x, y);
      if (!cut_by_walls(p, spans.spans, wall)) continue;
      ++cut;
      double length = 0;
      std::uint32_t kept = 0;
      for (; kept < p.count; ++kept) {
        Span& s = spans.spans[p.offset + kept];
        if (s.entry >= wall) break;
        s.exit = std::min(s.exit, wall);
        length += s.exit - s.entry;
      }
      p.count = p.total = kept;
      p.inside = static_cast<float>(length * spans.grid.view().ray_scale(x, y));
    }
  return cut;
}

bool reaches_past_walls(const SpanImage& spans, const Backdrop& backdrop) {
  check_size(spans, backdrop);
  const int width = spans.width();
  for (std::size_t i = 0; i < spans.pixels.size(); ++i)
    if (cut_by_walls(spans.pixels[i], spans.spans,
                     backdrop.wall_depth(int(i % std::size_t(width)), int(i / std::size_t(width)))))
      return true;
  return false;
}

}  // namespace voxspan
