#include "tools/scenes/span_compare.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "voxspan/error.h"

namespace voxspan::test {

double SpanComparison::inside_sum_error() const {
  if (inside_sum_reference == 0) return inside_sum_test == 0 ? 0 : 1;
  return std::abs(inside_sum_test - inside_sum_reference) / inside_sum_reference;
}

std::string SpanComparison::summary() const {
  std::ostringstream s;
  s << "pixels hit " << pixels_hit << ", count match " << count_match() * 100
    << " %, boundaries within " << boundary_match() * 100 << " % of " << boundaries << " (worst "
    << worst_boundary_layers << " layers), inside per pixel " << inside_match() * 100
    << " %, inside sum " << inside_sum_test << " vs " << inside_sum_reference << " ("
    << inside_sum_error() * 100 << " %)";
  return s.str();
}

SpanComparison compare_spans(const SpanImage& test, const SpanImage& ref, double layers) {
  SpanComparison c;
  const PerspectiveGrid& grid = ref.grid;
  // Slack for float rounding of layer depths (relative) on top of the layer bound.
  const auto allowed = [&](double depth) {
    return layers * grid.layer_thickness(depth) * 1.001 + 1e-6 * depth;
  };
  for (int y = 0; y < ref.height(); ++y)
    for (int x = 0; x < ref.width(); ++x) {
      const PixelSpans& a = test.pixel(x, y);
      const PixelSpans& b = ref.pixel(x, y);
      c.inside_sum_test += a.inside;
      c.inside_sum_reference += b.inside;
      if (a.total == 0 && b.total == 0) continue;
      ++c.pixels_hit;
      const auto sa = test.spans_at(x, y), sb = ref.spans_at(x, y);
      double deepest = 0;
      for (const Span& s : sa) deepest = std::max(deepest, double(s.exit));
      for (const Span& s : sb) deepest = std::max(deepest, double(s.exit));
      const double scale = grid.view().ray_scale(x, y);
      const double inside_allowed = 2.0 * std::max(a.total, b.total) * allowed(deepest) * scale;
      if (std::abs(double(a.inside) - double(b.inside)) <= inside_allowed) ++c.pixels_inside_within;
      if (a.count != b.count || a.total != b.total) continue;
      ++c.pixels_count_equal;
      for (std::size_t k = 0; k < sa.size(); ++k)
        for (int end = 0; end < 2; ++end) {
          const double t = end ? sa[k].exit : sa[k].entry;
          const double r = end ? sb[k].exit : sb[k].entry;
          ++c.boundaries;
          const double err = std::abs(t - r);
          c.worst_boundary_layers =
              std::max(c.worst_boundary_layers, err / grid.layer_thickness(r));
          if (err <= allowed(r)) ++c.boundaries_within;
        }
    }
  return c;
}

std::string describe_mismatches(const SpanImage& test, const SpanImage& ref, int most) {
  std::ostringstream s;
  s.precision(6);
  const auto list = [&](const SpanImage& image, int x, int y) {
    const PixelSpans& p = image.pixel(x, y);
    s << " (" << p.count << " of " << p.total << ")";
    for (const Span& span : image.spans_at(x, y))
      s << " [" << span.entry << " " << span.exit << "]";
  };
  for (int y = 0; y < ref.height() && most > 0; ++y)
    for (int x = 0; x < ref.width() && most > 0; ++x) {
      const PixelSpans& a = test.pixel(x, y);
      const PixelSpans& b = ref.pixel(x, y);
      if (a.count == b.count && a.total == b.total) continue;
      --most;
      s << "\npixel " << x << "," << y << "\n  test:";
      list(test, x, y);
      s << "\n  reference:";
      list(ref, x, y);
    }
  return s.str();
}

bool identical(const SpanImage& a, const SpanImage& b) { return same_spans(a, b, 0); }

bool same_spans(const SpanImage& a, const SpanImage& b, double inside_tolerance) {
  if (a.pixels.size() != b.pixels.size() || a.spans.size() != b.spans.size()) return false;
  // Offsets may differ only if the layout differs; compare records and each pixel's spans.
  for (std::size_t p = 0; p < a.pixels.size(); ++p) {
    const PixelSpans& x = a.pixels[p];
    const PixelSpans& y = b.pixels[p];
    const bool inside_same = inside_tolerance == 0
                                 ? std::memcmp(&x.inside, &y.inside, sizeof(float)) == 0
                                 : std::abs(double(x.inside) - y.inside) <=
                                       inside_tolerance * std::abs(double(y.inside));
    if (x.count != y.count || x.total != y.total || !inside_same) return false;
    if (x.count != 0 && std::memcmp(a.spans.data() + x.offset, b.spans.data() + y.offset,
                                    x.count * sizeof(Span)) != 0)
      return false;
  }
  return true;
}

namespace {

constexpr char kSpansMagic[8] = {'v', 'o', 'x', 's', 'p', 'a', 'n', '1'};

template <typename T> void write_array(std::ofstream& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
}

template <typename T>
std::vector<T> read_array(std::ifstream& in, std::uint64_t most,
                          const std::filesystem::path& path) {
  std::uint64_t n = 0;
  in.read(reinterpret_cast<char*>(&n), sizeof n);
  if (!in || n > most) throw make_error(path.string(), ": not a span file or truncated");
  std::vector<T> v(n);
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
  if (!in) throw make_error(path.string(), ": truncated");
  return v;
}

}  // namespace

void save_spans(const SpanImage& image, const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(kSpansMagic, sizeof kSpansMagic);
  write_array(out, image.pixels);
  write_array(out, image.spans);
  out.close();
  if (!out) throw make_error("cannot write ", path.string());
}

SpanImage load_spans(const std::filesystem::path& path, const PerspectiveGrid& grid) {
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof kSpansMagic] = {};
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kSpansMagic, sizeof magic) != 0)
    throw make_error(path.string(), ": cannot be read or is not a span file");
  SpanImage image;
  image.grid = grid;
  const std::uint64_t pixels = std::uint64_t(grid.width()) * std::uint64_t(grid.height());
  image.pixels = read_array<PixelSpans>(in, std::uint64_t(1) << 32, path);
  if (image.pixels.size() != pixels)
    throw make_error(path.string(), ": ", image.pixels.size(), " pixels, the grid has ", pixels);
  image.spans = read_array<Span>(in, std::uint64_t(1) << 34, path);
  for (const PixelSpans& p : image.pixels)
    if (std::uint64_t(p.offset) + p.count > image.spans.size())
      throw make_error(path.string(), ": a pixel's spans lie past the end of the file's spans");
  return image;
}

}  // namespace voxspan::test
