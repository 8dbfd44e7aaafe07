#include "insitu/parallel/span_merge.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "voxspan/error.h"

namespace voxspan {
namespace {

struct PixelHeader {
  std::uint32_t index, total, count;
  float inside;
};
static_assert(sizeof(PixelHeader) == 16);

void append(std::vector<std::byte>& out, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const std::byte*>(data);
  out.insert(out.end(), p, p + bytes);
}

// Walks an encoded band pixel by pixel.
class BandReader {
 public:
  explicit BandReader(std::span<const std::byte> bytes) : bytes_(bytes) {}
  // The next pixel and its spans; false at the end.
  bool next(PixelHeader& header, std::span<const Span>& spans) {
    if (at_ == bytes_.size()) return false;
    if (bytes_.size() - at_ < sizeof(PixelHeader)) throw make_error("span band cut short");
    std::memcpy(&header, bytes_.data() + at_, sizeof header);
    at_ += sizeof header;
    const std::size_t span_bytes = std::size_t(header.count) * sizeof(Span);
    if (bytes_.size() - at_ < span_bytes) throw make_error("span band cut short");
    spans = {reinterpret_cast<const Span*>(bytes_.data() + at_), header.count};
    at_ += span_bytes;
    return true;
  }

 private:
  std::span<const std::byte> bytes_;
  std::size_t at_ = 0;
};

void append_pixel(std::vector<std::byte>& out, const PixelHeader& header,
                  std::span<const Span> spans) {
  append(out, &header, sizeof header);
  append(out, spans.data(), spans.size_bytes());
}

// The compress pass's gap test (render/gl/passes/column_scan.glsl) in its own float arithmetic.
class GapRule {
 public:
  GapRule(const PerspectiveGrid& grid, int x, int y, double gap)
      : grid_(grid),
        near_(float(grid.near())),
        log2_step_(float(grid.log2_step())),
        centre_scale_(float(1 + grid.k_d() / 2)),
        scale_(ray_scale(grid, x, y)),
        gap_(float(gap)) {}
  // Whether the gap from a run ending at `exit` (a layer's depth) to one starting at `entry`
  // closes.
  bool closes(float exit, float entry) const {
    const float end = float(std::lround(grid_.layer_of(exit)));  // the layer after the run
    const float last_voxel = near_ * std::exp2((end - 1.0f) * log2_step_);
    return (entry - last_voxel) * centre_scale_ * scale_ < gap_;
  }

 private:
  // length(view_ray(pixel)) of render/gl/perspective_grid.glsl, in float.
  static float ray_scale(const PerspectiveGrid& grid, int x, int y) {
    const float nx = 2.0f * (float(x) + 0.5f) / float(grid.width()) - 1.0f;
    const float ny = 1.0f - 2.0f * (float(y) + 0.5f) / float(grid.height());
    const float vx = nx * float(grid.view().tan_half_x), vy = ny * float(grid.view().tan_half_y);
    return std::sqrt(vx * vx + vy * vy + 1.0f);
  }
  const PerspectiveGrid& grid_;
  const float near_, log2_step_, centre_scale_, scale_, gap_;
};

struct Entry {
  PixelHeader header;
  std::span<const Span> spans;
};

// One pixel of several ranks: the union of their spans, bridged and capped.
void merge_pixel(const PerspectiveGrid& grid, std::span<const Entry> entries,
                 const MergeSettings& settings, std::vector<Span>& scratch,
                 std::vector<Span>& merged, std::vector<std::byte>& out) {
  const std::uint32_t index = entries.front().header.index;
  const int x = int(index % std::uint32_t(grid.width())),
            y = int(index / std::uint32_t(grid.width()));
  const double scale = grid.view().ray_scale(x, y);
  scratch.clear();
  for (const Entry& e : entries) scratch.insert(scratch.end(), e.spans.begin(), e.spans.end());
  std::sort(scratch.begin(), scratch.end(),
            [](const Span& a, const Span& b) { return a.entry < b.entry; });
  // The gap rule of render/gl/passes/column_scan.glsl, between the centres of the last set voxel
  // (layer end - 1) and the next one, in float with the uniforms the compress pass gets, so
  // that a gap within rounding of g closes here as it would there.
  const GapRule rule(grid, x, y, settings.gap_bridging);
  auto bridged = [&](const Span& run, const Span& next) {
    if (next.entry <= run.exit) return true;  // touching or overlapping: one run of bits
    if (settings.exact_depths)
      return (double(next.entry) - double(run.exit)) * scale < settings.gap_bridging;
    return rule.closes(run.exit, next.entry);
  };
  merged.clear();
  SpanListBuilder list(merged, settings.max_spans);
  list.begin();
  Span run = scratch.front();
  for (std::size_t k = 1; k < scratch.size(); ++k) {
    if (bridged(run, scratch[k])) {
      run.exit = std::max(run.exit, scratch[k].exit);
      continue;
    }
    list.add(run.entry, run.exit, scale);
    run = scratch[k];
  }
  list.add(run.entry, run.exit, scale);
  const PixelSpans p = list.end();
  append_pixel(out, {index, p.total, p.count, p.inside}, merged);
}

// A lone rank's pixel, capped when the merge has a cap (ranks voxelize without one).
void copy_pixel(const Entry& e, const PerspectiveGrid& grid, const MergeSettings& settings,
                std::vector<Span>& merged, std::vector<std::byte>& out) {
  if (settings.max_spans == 0 || e.header.count <= settings.max_spans) {
    append_pixel(out, e.header, e.spans);
    return;
  }
  const std::uint32_t index = e.header.index;
  const double scale = grid.view().ray_scale(int(index % std::uint32_t(grid.width())),
                                             int(index / std::uint32_t(grid.width())));
  merged.clear();
  SpanListBuilder list(merged, settings.max_spans);
  list.begin();
  for (const Span& s : e.spans) list.add(s.entry, s.exit, scale);
  const PixelSpans p = list.end();
  append_pixel(out, {index, p.total, p.count, e.header.inside}, merged);
}

}  // namespace

std::vector<std::byte> encode_rows(const SpanImage& image, int row_begin, int row_end) {
  std::vector<std::byte> out;
  for (int y = row_begin; y < row_end; ++y)
    for (int x = 0; x < image.width(); ++x) {
      const PixelSpans& p = image.pixel(x, y);
      if (p.count == 0) continue;
      const auto index = std::uint32_t(x) + std::uint32_t(y) * std::uint32_t(image.width());
      append_pixel(out, {index, p.total, p.count, p.inside}, image.spans_at(x, y));
    }
  return out;
}

std::vector<std::byte> merge_rows(const PerspectiveGrid& grid,
                                  std::span<const std::vector<std::byte>> parts,
                                  const MergeSettings& settings) {
  // Each part lists its pixels in increasing index: merge them like sorted lists.
  // Only the parts with pixels take part: most are empty in a large job.
  std::vector<BandReader> readers;
  for (const std::vector<std::byte>& part : parts)
    if (!part.empty()) readers.emplace_back(part);
  std::vector<Entry> heads(readers.size());
  std::vector<bool> live(readers.size(), false);
  for (std::size_t r = 0; r < readers.size(); ++r)
    live[r] = readers[r].next(heads[r].header, heads[r].spans);
  std::vector<std::byte> out;
  std::vector<Entry> same;
  std::vector<Span> scratch, merged;
  for (;;) {
    std::uint32_t lowest = UINT32_MAX;
    for (std::size_t r = 0; r < readers.size(); ++r)
      if (live[r]) lowest = std::min(lowest, heads[r].header.index);
    if (lowest == UINT32_MAX) break;
    same.clear();
    for (std::size_t r = 0; r < readers.size(); ++r)
      if (live[r] && heads[r].header.index == lowest) {
        same.push_back(heads[r]);
        live[r] = readers[r].next(heads[r].header, heads[r].spans);
      }
    if (same.size() == 1) copy_pixel(same.front(), grid, settings, merged, out);
    else merge_pixel(grid, same, settings, scratch, merged, out);
  }
  return out;
}

SpanImage decode_image(const PerspectiveGrid& grid, std::span<const std::vector<std::byte>> bands) {
  SpanImage image;
  decode_image(grid, bands, image);
  return image;
}

void decode_image(const PerspectiveGrid& grid, std::span<const std::vector<std::byte>> bands,
                  SpanImage& image) {
  image.grid = grid;
  image.spans.clear();
  image.pixels.assign(std::size_t(grid.width()) * std::size_t(grid.height()), PixelSpans{});
  for (const std::vector<std::byte>& band : bands) {
    BandReader reader(band);
    PixelHeader h;
    std::span<const Span> spans;
    while (reader.next(h, spans)) {
      if (h.index >= image.pixels.size())
        throw make_error("span band: pixel ", h.index, " outside the image");
      image.pixels[h.index] = {std::uint32_t(image.spans.size()), h.count, h.total, h.inside};
      image.spans.insert(image.spans.end(), spans.begin(), spans.end());
    }
  }
}

RowBand band_of(int rank, int ranks, int height) {
  const auto row = [&](int r) { return int(std::int64_t(height) * r / ranks); };
  return {row(rank), row(rank + 1)};
}

}  // namespace voxspan
