#include "insitu/views/span_compositor.h"

#include "voxspan/error.h"

namespace voxspan {

std::vector<std::byte> SpanCompositor::merge(const SpanImage& local, FrameStats& stats) {
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
  std::int64_t pixels = 0;
  for (const auto& part : received) pixels += !part.empty();
  stats.set_count("composite.ranks_with_spans", pixels);
  return merge_rows(local.grid, received, settings_);
}

const GpuSpanImage* SpanCompositor::run(const GpuSpanImage* spans, const std::string& failure,
                                        gl::PassTimer& timer, FrameStats& stats) {
  const Agreement agreed = comm_.agree(spans != nullptr, failure);
  if (!agreed.ok) throw make_error("rank ", agreed.rank, ": ", agreed.message);
  SpanImage local;
  {
    auto t = timer.gpu("composite_download");
    local = spans->download();
  }
  std::vector<std::vector<std::byte>> bands;
  {
    auto t = timer.cpu("composite");
    const std::vector<std::byte> mine = merge(local, stats);
    bands = scheme_ == CompositeScheme::direct_send ? comm_.gather(mine)
                                                    : std::vector<std::vector<std::byte>>{mine};
  }
  stats.set_count("composite.bytes_sent", comm_.take_bytes_sent());
  if (!comm_.root()) return nullptr;
  auto t = timer.gpu("composite_upload");
  merged_.upload(decode_image(local.grid, bands));
  return &merged_;
}

}  // namespace voxspan
