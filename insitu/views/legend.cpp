#include "insitu/views/legend.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <span>

namespace voxspan {
namespace {

struct FontChar {
  char c;
  std::array<std::uint8_t, 7> rows;  // bit 4 is the leftmost pixel
};

// The classic 5x7 dot-matrix shapes.
constexpr FontChar kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
    {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}},
    {'x', {0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11}},
    {'y', {0x00, 0x00, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
    {'z', {0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F}},
    {'u', {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D}},
    {'v', {0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04}},
};

const FontChar* glyph(char c) {
  for (const FontChar& f : kFont)
    if (f.c == c) return &f;
  return nullptr;
}

void fill(FloatImage& p, int x0, int y0, int size, glm::vec3 colour) {
  for (int y = std::max(0, y0); y < std::min(p.height, y0 + size); ++y)
    for (int x = std::max(0, x0); x < std::min(p.width, x0 + size); ++x)
      p.set(x, y, glm::vec4(colour, 1.0f));
}

// One pass of the text in one colour, each font pixel grown by `grow` screen pixels per side.
void stamp(FloatImage& p, int x, int y, std::string_view text, int scale, glm::vec3 colour,
           int grow) {
  for (std::size_t n = 0; n < text.size(); ++n) {
    const FontChar* g = glyph(text[n]);
    if (g == nullptr) continue;
    const int left = x + int(n) * 6 * scale;
    for (int row = 0; row < 7; ++row)
      for (int col = 0; col < 5; ++col)
        if ((g->rows[std::size_t(row)] >> (4 - col)) & 1)
          fill(p, left + col * scale - grow, y + row * scale - grow, scale + 2 * grow, colour);
  }
}

}  // namespace

int text_scale(int image_height) { return std::max(1, image_height / 360); }

int text_width(std::string_view text, int scale) { return int(text.size()) * 6 * scale; }

void draw_text(FloatImage& picture, int x, int y, std::string_view text, int scale,
               glm::vec3 colour) {
  // A dark outline first, so that the text reads on any colour.
  stamp(picture, x, y, text, scale, glm::vec3(0.0f), std::max(1, scale / 2));
  stamp(picture, x, y, text, scale, colour, 0);
}

std::string legend_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

void draw_color_bar(FloatImage& picture, ColorMap map, double lo, double hi, BarSide side) {
  const int w = picture.width, h = picture.height;
  const int bar = std::max(4, w / 40), top = h / 10, bottom = h - h / 10;
  const int x0 = side == BarSide::right ? w - 2 * bar : bar;
  if (x0 <= 0 || bottom - top < 2) return;
  for (int j = top; j < bottom; ++j)
    for (int i = x0; i < x0 + bar; ++i)
      picture.set(
          i, j, glm::vec4(map_color(map, double(bottom - 1 - j) / double(bottom - 1 - top)), 1.0f));
  const int s = text_scale(h), gap = bar / 2 + s;
  const auto label = [&](double v, int centre_y) {
    const std::string t = legend_number(v);
    const int x = side == BarSide::right ? x0 - gap - text_width(t, s) : x0 + bar + gap;
    draw_text(picture, x, centre_y - 7 * s / 2, t, s);
  };
  label(hi, top);
  label(0.5 * (lo + hi), (top + bottom - 1) / 2);
  label(lo, bottom - 1);
}

namespace {

// About five round values inside [min(from, to), max(from, to)]: multiples of 1, 2 or 5 times
// a power of ten. The step is at least span / 7.5, so there are at most 8 (+1 for rounding).
struct Ticks {
  std::array<double, 10> values;
  std::size_t count = 0;
};
Ticks ticks(double from, double to) {
  Ticks out;
  const double lo = std::min(from, to), hi = std::max(from, to), span = hi - lo;
  if (!(span > 0) || !std::isfinite(span)) return out;
  const double raw = span / 5, power = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / power < 1.5 ? power : raw / power < 3.5 ? 2 * power : 5 * power;
  for (double n = std::ceil(lo / step); n * step <= hi && out.count < out.values.size(); n += 1)
    out.values[out.count++] = std::abs(n) < 0.5 ? 0.0 : n * step;  // an exact 0, never -1e-17
  return out;
}

std::string tick_label(double value, const Axis& axis, bool named) {
  return named ? std::string(axis.name) + "=" + legend_number(value) : legend_number(value);
}

void fill_rect(FloatImage& p, int x0, int y0, int x1, int y1, glm::vec3 colour) {
  for (int y = std::max(0, y0); y < std::min(p.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(p.width, x1); ++x) p.set(x, y, glm::vec4(colour, 1));
}

}  // namespace

void draw_axes(FloatImage& picture, const Axis& horizontal, const Axis& vertical) {
  const int w = picture.width, h = picture.height, s = text_scale(h), mark = 4 * s;
  if (w < kAxesMinWidth || h < kAxesMinHeight) return;
  const glm::vec3 light(0.9f);
  const Ticks xt = ticks(horizontal.from, horizontal.to);
  const std::span<const double> xs(xt.values.data(), xt.count);
  for (std::size_t n = 0; n < xs.size(); ++n) {
    const int x = int(
                  std::lround((xs[n] - horizontal.from) / (horizontal.to - horizontal.from) * w)),
              thick = std::max(1, s / 2 + 1);
    fill_rect(picture, x - thick / 2, h - mark, x - thick / 2 + thick, h, light);
    const std::string t = tick_label(xs[n], horizontal, n == xs.size() / 2);
    const int left = std::clamp(x - text_width(t, s) / 2, s, std::max(s, w - text_width(t, s)));
    draw_text(picture, left, h - mark - s - 7 * s, t, s);
  }
  const Ticks yt = ticks(vertical.from, vertical.to);
  const std::span<const double> ys(yt.values.data(), yt.count);
  for (std::size_t n = 0; n < ys.size(); ++n) {
    const int y = h - int(std::lround((ys[n] - vertical.from) / (vertical.to - vertical.from) * h)),
              thick = std::max(1, s / 2 + 1);
    if (y > h - 3 * mark - 7 * s) continue;  // leave the corner to the bottom axis's labels
    // The value sits on its tick, which underlines it (beside it, a tick reads as a minus).
    const std::string t = tick_label(ys[n], vertical, n == ys.size() / 2);
    fill_rect(picture, 0, y - thick / 2, s + text_width(t, s), y - thick / 2 + thick, light);
    draw_text(picture, s, std::max(s, y - 9 * s), t, s);
  }
}

}  // namespace voxspan
