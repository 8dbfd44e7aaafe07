#include "insitu/views/volume_compositor.h"

#include <exception>

#include <tbb/parallel_for.h>

#include "insitu/parallel/byte_packing.h"
#include "insitu/parallel/span_merge.h"
#include "insitu/views/view.h"
#include "render/volume_merge.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

using Bytes = std::vector<std::byte>;

// A message of the composite, read.
struct Reader : Unpacker {
  explicit Reader(std::span<const std::byte> bytes)
      : Unpacker(bytes, "a volume composite message") {}
};

std::vector<Bytes> bytes_of(std::vector<Packer>& packed) {
  std::vector<Bytes> out;
  for (Packer& p : packed) out.push_back(std::move(p.bytes));
  return out;
}

// Runs `step`; false with its message when it throws.
template <class F> bool attempt(F&& step, std::string& failure) {
  try {
    step();
    return true;
  } catch (const std::exception& e) {
    failure = e.what();
    return false;
  }
}

// One rank's items on the pixels of a band, as the merge reads them.
struct RankItems {
  std::vector<std::int32_t> slot;  // per pixel of the band: its place in the lists; -1: none
  std::vector<std::uint32_t> raw_start, segment_start;  // per listed pixel, then the total
  std::vector<RawSample> raws;
  std::vector<PartSegment> segments;
};

// On the wire a pixel's shared sums go as runs of consecutive samples, each its first index and
// count, then the sums as float pairs (a third of the bytes of an index and two doubles per
// sample; the owner adds them in double: the merge's picture moves by rounding, 1e-7).
struct RawRun {
  std::int32_t first;
  std::uint32_t count;
};
struct RawSums {
  float s, w;
};

RankItems read_items(std::span<const std::byte> bytes, std::size_t band_first,
                     std::size_t band_pixels) {
  RankItems items;
  items.slot.assign(band_pixels, -1);
  items.raw_start.push_back(0);
  items.segment_start.push_back(0);
  Reader in(bytes);
  std::vector<RawSums> sums;
  items.raws.reserve(bytes.size() / sizeof(RawSums));  // at most: the bytes are mostly sums
  while (!in.done()) {
    items.slot.at(in.get<std::uint32_t>() - band_first) = std::int32_t(items.raw_start.size() - 1);
    const auto runs = in.get<std::uint32_t>(), segments = in.get<std::uint32_t>();
    for (std::uint32_t k = 0; k < runs; ++k) {
      const RawRun run = in.get<RawRun>();
      sums.clear();
      in.get_span(run.count, sums);
      for (std::uint32_t i = 0; i < run.count; ++i)
        items.raws.push_back({run.first + std::int32_t(i), sums[i].s, sums[i].w});
    }
    in.get_span(segments, items.segments);
    items.raw_start.push_back(std::uint32_t(items.raws.size()));
    items.segment_start.push_back(std::uint32_t(items.segments.size()));
  }
  return items;
}

Bytes encode_items(const VolumePart& part, RowBand band) {
  Packer out;
  const std::size_t width = std::size_t(part.width);
  const std::size_t first = std::size_t(band.begin) * width, end = std::size_t(band.end) * width;
  out.bytes.reserve((part.raw_start[end] - part.raw_start[first]) * sizeof(RawSums) +
                    (part.segment_start[end] - part.segment_start[first]) * sizeof(PartSegment));
  std::vector<RawRun> runs;
  std::vector<RawSums> sums;
  for (std::size_t p = first; p < end; ++p) {
    const std::span<const RawSample> raws = part.raws_of(p);
    const std::span<const PartSegment> segments = part.segments_of(p);
    if (raws.empty() && segments.empty()) continue;
    runs.clear();
    for (std::size_t k = 0; k < raws.size(); ++k)
      if (!runs.empty() && raws[k].index == runs.back().first + std::int32_t(runs.back().count))
        ++runs.back().count;
      else runs.push_back({raws[k].index, 1});
    out.put(std::uint32_t(p));
    out.put(std::uint32_t(runs.size()));
    out.put(std::uint32_t(segments.size()));
    std::size_t k = 0;
    for (const RawRun& run : runs) {
      out.put(run);
      sums.clear();
      for (std::uint32_t i = 0; i < run.count; ++i, ++k)
        sums.push_back({float(raws[k].s), float(raws[k].w)});
      out.put_span<RawSums>(sums);
    }
    out.put_span(segments);
  }
  return std::move(out.bytes);
}

// Per rank, the samples of its hulls on `band` that other ranks' hulls hold too.
std::vector<Bytes> shared_replies(std::span<const Bytes> hulls, RowBand band, int width) {
  const std::size_t ranks = hulls.size();
  const std::size_t first = std::size_t(band.begin) * std::size_t(width);
  const std::size_t pixels = std::size_t(band.end - band.begin) * std::size_t(width);
  std::vector<std::vector<SampleRange>> by_rank(ranks);
  std::vector<std::uint8_t> holders(pixels, 0);
  for (std::size_t r = 0; r < ranks; ++r) {
    by_rank[r].assign(pixels, SampleRange{});
    Reader in(hulls[r]);
    while (!in.done()) {
      const std::size_t p = in.get<std::uint32_t>() - first;
      by_rank[r][p] = in.get<SampleRange>();
      holders[p] = std::uint8_t(std::min(2, holders[p] + 1));
    }
  }
  std::vector<Packer> replies(ranks);
  std::vector<SampleRange> of_pixel(ranks);
  std::vector<std::vector<SampleRange>> cut(ranks);
  for (std::size_t p = 0; p < pixels; ++p) {
    if (holders[p] < 2) continue;
    for (std::size_t r = 0; r < ranks; ++r) {
      of_pixel[r] = by_rank[r][p];
      cut[r].clear();
    }
    shared_ranges(of_pixel, cut);
    for (std::size_t r = 0; r < ranks; ++r) {
      if (cut[r].empty()) continue;
      replies[r].put(std::uint32_t(first + p));
      replies[r].put(std::uint32_t(cut[r].size()));
      replies[r].put_span<SampleRange>(cut[r]);
    }
  }
  return bytes_of(replies);
}

// The owners' replies (in rank order: bands in row order) as per-pixel ranges.
void read_shared(std::span<const Bytes> replies, std::size_t pixels, PixelRanges& out) {
  out.start.assign(pixels + 1, 0);
  out.ranges.clear();
  std::size_t next = 0;  // the first pixel whose start is not set yet
  for (const Bytes& reply : replies) {
    Reader in(reply);
    while (!in.done()) {
      const std::size_t p = in.get<std::uint32_t>();
      const auto n = in.get<std::uint32_t>();
      for (; next <= p; ++next) out.start[next] = std::uint32_t(out.ranges.size());
      in.get_span(n, out.ranges);
    }
  }
  for (; next <= pixels; ++next) out.start[next] = std::uint32_t(out.ranges.size());
}

bool zero(const FieldSums& f) { return f.s == 0 && f.w == 0; }

}  // namespace

void VolumeCompositor::agree(bool ok, const std::string& failure) {
  comm_.agree_or_throw(ok, failure);
}

bool VolumeCompositor::render(VolumeRenderer& renderer, const Camera& camera,
                              std::span<const VolumeParticle> particles,
                              const VolumeOptions& options, bool deep, Recorder& recorder,
                              VolumeFrame& out) {
  const int ranks = comm_.size();
  const std::size_t rank_count = std::size_t(ranks);
  const std::int64_t bytes_before = comm_.bytes_sent();
  const RowBand mine = band_of(comm_.rank(), ranks, camera.height);
  const std::size_t width = std::size_t(camera.width);
  const std::size_t pixels = width * std::size_t(camera.height);
  const std::size_t band_first = std::size_t(mine.begin) * width;
  std::string failure;
  VolumeCounts counts;
  // Adaptive sampling: each rank's cells may change the composited picture by their share of the
  // tolerance; the shares add up to it (render/cpu/volume_adaptive.h: front to back, a cell's
  // change is at most its term whatever the other ranks' samples around it, so the ranks' terms
  // add).
  VolumeOptions mine_options = options;
  mine_options.adaptive.share = options.adaptive.share / double(ranks);

  agree(attempt([&] { counts = renderer.cover(camera, particles, mine_options, recorder, hulls_); },
                failure),
        failure);
  {
    auto t = recorder.host(pass::composite);
    std::vector<Packer> send(rank_count);
    for (int r = 0; r < ranks; ++r) {
      const RowBand band = band_of(r, ranks, camera.height);
      for (std::size_t p = std::size_t(band.begin) * width; p < std::size_t(band.end) * width; ++p)
        if (!hulls_[p].empty()) {
          send[std::size_t(r)].put(std::uint32_t(p));
          send[std::size_t(r)].put(hulls_[p]);
        }
    }
    const std::vector<Bytes> hulls = comm_.exchange(bytes_of(send));
    read_shared(comm_.exchange(shared_replies(hulls, mine, camera.width)), pixels, shared_);
  }

  agree(attempt([&] { counts += renderer.render_part(shared_, recorder, part_); }, failure),
        failure);
  ParallelVolumeMerge merge(camera, options, deep);
  {
    auto t = recorder.host(pass::composite);
    std::vector<Bytes> send(rank_count);
    for (int r = 0; r < ranks; ++r)
      send[std::size_t(r)] = encode_items(part_, band_of(r, ranks, camera.height));
    const std::vector<Bytes> received = comm_.exchange(send);
    const std::size_t band_pixels = std::size_t(mine.end) * width - band_first;
    std::vector<RankItems> items(received.size());
    tbb::parallel_for(std::size_t(0), received.size(), [&](std::size_t r) {
      items[r] = read_items(received[r], band_first, band_pixels);
    });
    merge.merge(
        band_first, band_pixels, items.size(), [&](std::size_t p, auto& raws, auto& segments) {
          for (std::size_t r = 0; r < items.size(); ++r) {
            const RankItems& it = items[r];
            const std::int32_t k = it.slot[p - band_first];
            raws[r] = {};
            segments[r] = {};
            if (k < 0) continue;
            const std::size_t i = std::size_t(k);
            raws[r] = {it.raws.data() + it.raw_start[i], it.raw_start[i + 1] - it.raw_start[i]};
            segments[r] = {it.segments.data() + it.segment_start[i],
                           it.segment_start[i + 1] - it.segment_start[i]};
          }
        });
  }
  const std::vector<HitQuery>& queries = merge.queries();

  std::vector<FieldSums> sums(queries.size());
  if (options.mode != VolumeMode::dvr) {
    std::vector<Bytes> asked;
    {
      auto t = recorder.host(pass::composite);
      Packer mine_asked;
      mine_asked.put_span<HitQuery>(queries);
      asked = comm_.exchange(std::vector<Bytes>(rank_count, mine_asked.bytes));
    }
    std::vector<Packer> answers(rank_count);
    agree(attempt(
              [&] {
                std::vector<HitQuery> q;
                std::vector<FieldSums> found;
                for (std::size_t owner = 0; owner < asked.size(); ++owner) {
                  q.clear();
                  found.clear();
                  Reader(asked[owner]).get_span(asked[owner].size() / sizeof(HitQuery), q);
                  renderer.field_sums(q, recorder, found);
                  for (std::size_t k = 0; k < found.size(); ++k)
                    if (!zero(found[k])) {
                      answers[owner].put(std::uint32_t(k));
                      answers[owner].put(found[k]);
                    }
                }
              },
              failure),
          failure);
    auto t = recorder.host(pass::composite);
    for (const Bytes& answer : comm_.exchange(bytes_of(answers))) {
      Reader in(answer);
      while (!in.done()) {
        const std::size_t k = in.get<std::uint32_t>();
        sums.at(k) += in.get<FieldSums>();
      }
    }
  }

  std::vector<std::vector<std::byte>> bands;
  {
    auto t = recorder.host(pass::composite);
    std::vector<glm::vec4> colors;
    std::vector<float> depths;
    std::vector<std::uint32_t> deep_counts;
    std::vector<DeepSample> deep_samples;
    merge.finish(sums, colors, depths, &deep_counts, &deep_samples);
    Packer band;
    band.put_span<glm::vec4>(colors);
    band.put_span<float>(depths);
    if (deep) {
      band.put_span<std::uint32_t>(deep_counts);
      band.put_span<DeepSample>(deep_samples);
    }
    bands = comm_.gather(band.bytes);
  }
  counts += merge.counts();
  record(counts, recorder);  // this rank's: the stats line sums them over the ranks
  recorder.count(counter::composite_bytes_sent, comm_.bytes_sent() - bytes_before);
  if (!comm_.root()) return false;

  out.reset(camera.width, camera.height);
  DeepImage& image = out.deep;
  image = {camera.width, camera.height, {0}, {}};
  for (int r = 0; r < ranks; ++r) {
    const RowBand band = band_of(r, ranks, camera.height);
    const std::size_t n = std::size_t(band.end - band.begin) * width;
    std::vector<glm::vec4> colors;
    std::vector<float> depths;
    std::vector<std::uint32_t> deep_counts;
    Reader in(bands[std::size_t(r)]);
    in.get_span(n, colors);
    in.get_span(n, depths);
    if (deep) in.get_span(n, deep_counts);
    std::size_t samples = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t p = std::size_t(band.begin) * width + k;
      out.picture.set(int(p % width), int(p / width), colors[k]);
      out.depth[p] = depths[k];
      if (!deep) continue;
      samples += deep_counts[k];
      image.start.push_back(image.start.back() + deep_counts[k]);
    }
    if (deep) in.get_span(samples, image.samples);
  }
  if (!deep) image = {};
  return true;
}

}  // namespace voxspan
