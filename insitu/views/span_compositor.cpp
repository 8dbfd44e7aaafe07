#include "insitu/views/span_compositor.h"

#include "voxspan/error.h"

namespace voxspan {

std::vector<std::byte> SpanCompositor::merge(const SpanImage& local, Recorder& recorder) {
  const int ranks = comm_.size(), height = local.height();
  std::vector<std::vector<std::byte>> received;
  if (scheme_ == CompositeScheme::direct_send) {
    std::vector<std::vector<std::byte>> send(static_cast<std::size_t>(ranks));
    for (int r = 0; r < ranks; ++r) {
      const RowBand band = band_of(r, ranks, height);
      send[std::size_t(r)] = encode_rows(local, band.begin, band.end);
    }
    received = comm_.exchange(send);
  } else {
    received = comm_.gather(encode_rows(local, 0, height));
    if (!comm_.root()) return {};
  }
  std::int64_t senders = 0;
  for (const auto& part : received) senders += !part.empty();
  recorder.count(counter::composite_ranks_with_spans, senders);
  return merge_rows(local.grid, received, settings_);
}

void SpanCompositor::agree(bool ok, const std::string& failure) {
  comm_.agree_or_throw(ok, failure);
}

bool SpanCompositor::composite(const SpanImage& local, std::int64_t bytes_before,
                               Recorder& recorder) {
  std::vector<std::vector<std::byte>> bands;
  {
    auto t = recorder.host(pass::composite);
    std::vector<std::byte> mine = merge(local, recorder);
    if (scheme_ == CompositeScheme::direct_send) bands = comm_.gather(mine);
    else bands.push_back(std::move(mine));
  }
  recorder.count(counter::composite_bytes_sent, comm_.bytes_sent() - bytes_before);
  if (!comm_.root()) return false;
  decode_image(local.grid, bands, composite_);
  return true;
}

const SpanImage* SpanCompositor::run(const SpanImage* spans, const std::string& failure,
                                     Recorder& recorder) {
  const std::int64_t bytes_before = comm_.bytes_sent();
  agree(spans != nullptr, failure);
  return composite(*spans, bytes_before, recorder) ? &composite_ : nullptr;
}

}  // namespace voxspan
