#include "insitu/views/legend.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <span>

namespace voxspan {
namespace {

// The longest legend_number short of exponents of three digits ("%.3g": -0.000125).
constexpr std::string_view kLongestNumber = "-0.000125";

struct FontChar {
  char c;
  std::array<std::uint8_t, 7> rows;  // bit 4 is the leftmost pixel
};

// The classic 5x7 dot-matrix shapes of printable ASCII, '!' to '~' in order (a space is blank).
constexpr FontChar kFont[] = {
    {'!', {0x04, 0x04, 0x04, 0x04, 0x04, 0x00, 0x04}},
    {'"', {0x0A, 0x0A, 0x0A, 0x00, 0x00, 0x00, 0x00}},
    {'#', {0x0A, 0x0A, 0x1F, 0x0A, 0x1F, 0x0A, 0x0A}},
    {'$', {0x04, 0x0F, 0x14, 0x0E, 0x05, 0x1E, 0x04}},
    {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'&', {0x0C, 0x12, 0x14, 0x08, 0x15, 0x12, 0x0D}},
    {'\'', {0x04, 0x04, 0x08, 0x00, 0x00, 0x00, 0x00}},
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
    {'*', {0x00, 0x04, 0x15, 0x0E, 0x15, 0x04, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
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
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
    {';', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x04, 0x08}},
    {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}},
    {'?', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}},
    {'@', {0x0E, 0x11, 0x01, 0x0D, 0x15, 0x15, 0x0E}},
    {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
    {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
    {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}},
    {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}},
    {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
    {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}},
    {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x0A, 0x04, 0x04, 0x04, 0x04}},
    {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'[', {0x0E, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0E}},
    {'\\', {0x00, 0x10, 0x08, 0x04, 0x02, 0x01, 0x00}},
    {']', {0x0E, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0E}},
    {'^', {0x04, 0x0A, 0x11, 0x00, 0x00, 0x00, 0x00}},
    {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
    {'`', {0x08, 0x04, 0x02, 0x00, 0x00, 0x00, 0x00}},
    {'a', {0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F}},
    {'b', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E}},
    {'c', {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}},
    {'d', {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F}},
    {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
    {'f', {0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08}},
    {'g', {0x00, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
    {'h', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'i', {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}},
    {'j', {0x02, 0x00, 0x06, 0x02, 0x02, 0x12, 0x0C}},
    {'k', {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}},
    {'l', {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}},
    {'n', {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'o', {0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E}},
    {'p', {0x00, 0x00, 0x1E, 0x11, 0x1E, 0x10, 0x10}},
    {'q', {0x00, 0x00, 0x0D, 0x13, 0x0F, 0x01, 0x01}},
    {'r', {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10}},
    {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}},
    {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}},
    {'u', {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D}},
    {'v', {0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'w', {0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A}},
    {'x', {0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11}},
    {'y', {0x00, 0x00, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
    {'z', {0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F}},
    {'{', {0x02, 0x04, 0x04, 0x08, 0x04, 0x04, 0x02}},
    {'|', {0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'}', {0x08, 0x04, 0x04, 0x02, 0x04, 0x04, 0x08}},
    {'~', {0x00, 0x00, 0x08, 0x15, 0x02, 0x00, 0x00}},
};
constexpr char kFirst = '!', kLast = '~';

constexpr bool in_order() {
  for (std::size_t i = 0; i < std::size(kFont); ++i)
    if (kFont[i].c != char(kFirst + int(i))) return false;
  return std::size(kFont) == std::size_t(kLast - kFirst + 1);
}
static_assert(in_order(), "kFont holds every printable character, in order");

const FontChar* glyph(char c) { return c >= kFirst && c <= kLast ? &kFont[c - kFirst] : nullptr; }

// A colour as each kind of picture stores it: the 8-bit one's bytes are linear_to_srgb8 of the
// float one's, so that text drawn on either is the same once encoded
// (tests/insitu/views/test_shared_picture.cpp).
glm::vec4 stored(const FloatImage&, glm::vec3 colour) { return glm::vec4(colour, 1.0f); }
std::array<std::uint8_t, 4> stored(const ImageRGBA8&, glm::vec3 colour) {
  return {linear_to_srgb8(colour.r), linear_to_srgb8(colour.g), linear_to_srgb8(colour.b), 255};
}
void put(FloatImage& p, int x, int y, glm::vec4 c) { p.set(x, y, c); }
void put(ImageRGBA8& p, int x, int y, const std::array<std::uint8_t, 4>& c) {
  std::copy(c.begin(), c.end(),
            p.pixels.begin() + (std::ptrdiff_t(x) + std::ptrdiff_t(y) * p.width) * 4);
}

template <class Image> void fill(Image& p, int x0, int y0, int size, glm::vec3 colour) {
  const auto c = stored(p, colour);
  for (int y = std::max(0, y0); y < std::min(p.height, y0 + size); ++y)
    for (int x = std::max(0, x0); x < std::min(p.width, x0 + size); ++x) put(p, x, y, c);
}

// One pass of the text in one colour, each font pixel grown by `grow` screen pixels per side.
template <class Image>
void stamp(Image& p, int x, int y, std::string_view text, int scale, glm::vec3 colour, int grow) {
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

template <class Image>
void draw_text_on(Image& picture, int x, int y, std::string_view text, int scale,
                  glm::vec3 colour) {
  // A dark outline first, so that the text reads on any colour.
  stamp(picture, x, y, text, scale, glm::vec3(0.0f), std::max(1, scale / 2));
  stamp(picture, x, y, text, scale, colour, 0);
}

template <class Image> void draw_caption_on(Image& picture, std::string_view text) {
  const int s = text_scale(picture.height);
  draw_text_on(picture, 3 * s, 3 * s, text, s, kTextColour);
}

}  // namespace

int text_scale(int image_height) { return std::max(1, image_height / 360); }

int text_width(std::string_view text, int scale) { return int(text.size()) * 6 * scale; }

void draw_text(FloatImage& picture, int x, int y, std::string_view text, int scale,
               glm::vec3 colour) {
  draw_text_on(picture, x, y, text, scale, colour);
}

LegendMargins legend_margins(int width, int height) {
  const int s = text_scale(height);
  const int label = text_width(kLongestNumber, s);
  LegendMargins m{.left = s + label + s,
                  .right = color_bar_columns(width, height),
                  .top = 3 * s + 7 * s + 2 * s,
                  .bottom = 4 * s + s + 7 * s + 2 * s};
  if (width - m.left - m.right < width / 2 || height - m.top - m.bottom < height / 2) return {};
  return m;
}

void draw_caption(FloatImage& picture, std::string_view text) { draw_caption_on(picture, text); }

void draw_caption(ImageRGBA8& picture, std::string_view text) { draw_caption_on(picture, text); }

std::string legend_number(double value, double apart) {
  int digits = 3;
  if (apart > 0 && std::isfinite(apart) && std::isfinite(value)) {
    if (std::abs(value) < 1e-6 * apart) value = 0;
    if (value != 0)
      digits = std::clamp(int(std::floor(std::log10(std::abs(value) / apart))) + 2, 3, 15);
  }
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

namespace {

// The colour bar's layout: the bar `bar` pixels wide, one bar's width from the picture's edge,
// over rows [top, bottom); its values `gap` pixels from it on the side away from the edge.
struct BarLayout {
  int bar, top, bottom, gap, scale;
  BarLayout(int w, int h)
      : bar(std::max(4, w / 40)),
        top(h / 10),
        bottom(h - h / 10),
        gap(bar / 2 + text_scale(h)),
        scale(text_scale(h)) {}
};

}  // namespace

int color_bar_columns(int width, int height) {
  const BarLayout l(width, height);
  return 2 * l.bar + l.gap + text_width(kLongestNumber, l.scale) + l.scale;  // + the outline
}

LegendMargins color_bar_margins(int width, int height, BarSide side) {
  const int columns = color_bar_columns(width, height);
  if (width - columns < width / 2) return {};
  return side == BarSide::right ? LegendMargins{.right = columns} : LegendMargins{.left = columns};
}

LegendMargins covering(const LegendMargins& a, const LegendMargins& b) {
  return {.left = std::max(a.left, b.left),
          .right = std::max(a.right, b.right),
          .top = std::max(a.top, b.top),
          .bottom = std::max(a.bottom, b.bottom)};
}

void draw_color_bar(FloatImage& picture, ColorMap map, const ColorAxis& axis,
                    std::string_view title, BarSide side) {
  const int w = picture.width, h = picture.height;
  const BarLayout l(w, h);
  const int bar = l.bar, top = l.top, bottom = l.bottom;
  const int x0 = side == BarSide::right ? w - 2 * bar : bar;
  if (x0 <= 0 || bottom - top < 2) return;
  for (int j = top; j < bottom; ++j)
    for (int i = x0; i < x0 + bar; ++i)
      picture.set(
          i, j, glm::vec4(map_color(map, double(bottom - 1 - j) / double(bottom - 1 - top)), 1.0f));
  const int s = l.scale, gap = l.gap;
  const double middle = axis.value(0.5);
  const double apart = std::min(std::abs(axis.hi - middle), std::abs(middle - axis.lo));
  const auto label = [&](double v, int centre_y) {
    const std::string t = legend_number(v, apart);
    const int x = side == BarSide::right ? x0 - gap - text_width(t, s) : x0 + bar + gap;
    draw_text(picture, x, centre_y - 7 * s / 2, t, s);
  };
  label(axis.hi, top);
  label(middle, (top + bottom - 1) / 2);
  label(axis.lo, bottom - 1);
  // Above the top value's label with a line's height between them where the picture has room
  // (closer, they read as one line), flush with the bar's outer edge.
  const int title_x = side == BarSide::right ? x0 + bar - text_width(title, s) : x0;
  const int label_top = top - 7 * s / 2, spaced = label_top - 7 * s - 7 * s;
  draw_text(picture, std::max(0, title_x), spaced >= s ? spaced : label_top - 3 * s - 7 * s, title,
            s);
}

namespace {

// About five round values inside [min(from, to), max(from, to)]: multiples of 1, 2 or 5 times
// a power of ten. The step is at least span / 7.5, so there are at most 8 (+1 for rounding).
struct Ticks {
  std::array<double, 10> values;
  std::size_t count = 0;
  double step = 0;
};
Ticks ticks(double from, double to) {
  Ticks out;
  const double lo = std::min(from, to), hi = std::max(from, to), span = hi - lo;
  if (!(span > 0) || !std::isfinite(span)) return out;
  const double raw = span / 5, power = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / power < 1.5 ? power : raw / power < 3.5 ? 2 * power : 5 * power;
  out.step = step;
  for (double n = std::ceil(lo / step); n * step <= hi && out.count < out.values.size(); n += 1)
    out.values[out.count++] = std::abs(n) < 0.5 ? 0.0 : n * step;  // an exact 0, never -1e-17
  return out;
}

std::string tick_label(double value, double step, const Axis& axis, bool named) {
  const std::string number = legend_number(value, step);
  return named ? std::string(axis.name) + "=" + number : number;
}

// Every how many ticks along a horizontal axis `width` pixels wide carry their label, so that the
// labels (every one as wide as the widest) do not run into each other.
std::size_t label_every(const Ticks& t, const Axis& axis, int width, int scale) {
  int widest = 0;
  for (std::size_t n = 0; n < t.count; ++n)
    widest = std::max(widest,
                      text_width(tick_label(t.values[n], t.step, axis, n == t.count / 2), scale));
  for (std::size_t every = 1; every < t.count; ++every)
    if (int((t.count + every - 1) / every) * (widest + 2 * 6 * scale) <= width) return every;
  return std::max<std::size_t>(t.count, 1);
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
  const std::size_t every = label_every(xt, horizontal, w, s), named = xs.size() / 2;
  for (std::size_t n = 0; n < xs.size(); ++n) {
    const int x = int(
                  std::lround((xs[n] - horizontal.from) / (horizontal.to - horizontal.from) * w)),
              thick = std::max(1, s / 2 + 1);
    fill_rect(picture, x - thick / 2, h - mark, x - thick / 2 + thick, h, light);
    // Labels on every `every`-th tick, counted from the middle one, which names the axis.
    if ((n > named ? n - named : named - n) % every != 0) continue;
    const std::string t = tick_label(xs[n], xt.step, horizontal, n == named);
    const int left = std::clamp(x - text_width(t, s) / 2, s, std::max(s, w - text_width(t, s)));
    draw_text(picture, left, h - mark - s - 7 * s, t, s);
  }
  const Ticks yt = ticks(vertical.from, vertical.to);
  const std::span<const double> ys(yt.values.data(), yt.count);
  for (std::size_t n = 0; n < ys.size(); ++n) {
    const int y = h - int(std::lround((ys[n] - vertical.from) / (vertical.to - vertical.from) * h)),
              thick = std::max(1, s / 2 + 1);
    if (y > h - 3 * mark - 7 * s) continue;  // leave the corner to the bottom axis's labels
    if (y - 9 * s < 12 * s) continue;        // and the top row to the caption
    // The value sits on its tick, which underlines it (beside it, a tick reads as a minus).
    const std::string t = tick_label(ys[n], yt.step, vertical, n == ys.size() / 2);
    fill_rect(picture, 0, y - thick / 2, s + text_width(t, s), y - thick / 2 + thick, light);
    draw_text(picture, s, std::max(s, y - 9 * s), t, s);
  }
}

}  // namespace voxspan
