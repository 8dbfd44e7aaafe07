// insitu/views/span_compositor.h - the span stage of a view rendered by several MPI ranks:
// every rank's span image (all made in the same perspective grid: DepthRangeCombine) merged
// exactly (insitu/parallel/span_merge.h) into the one the root shades. docs/design.md,
// "Compositing across ranks", says which scheme and why, with the figures.
//   direct send: the image's rows are cut into one band per rank; each rank sends every other
//     rank the pixels of its band that it has spans in (a rank with nothing in view sends only
//     the counts), merges the band it owns, and the bands are gathered on the root;
//   root: every rank sends all its pixels to the root, which merges the whole image (the
//     simplest, for comparison: its root receives everything).
// Counts per step: composite.bytes_sent (this rank), composite.ranks_with_spans (the ranks that
// sent this rank pixels of the bands it merges; on the root under `root`). Times: composite (the
// exchange and the merge); the surface view adds, with the GL renderer, the span image's
// transfers around it (pass::composite_download, pass::composite_upload: insitu/views/view.h).
#pragma once

#include <string>

#include "insitu/parallel/communicator.h"
#include "insitu/parallel/span_merge.h"
#include "insitu/views/view.h"

namespace voxspan {

namespace counter {
inline constexpr StatName composite_ranks_with_spans{"composite.ranks_with_spans"};
}  // namespace counter

class SpanCompositor final : public SpanStage {
 public:
  SpanCompositor(Communicator& comm, const MergeSettings& settings, CompositeScheme scheme)
      : comm_(comm), settings_(settings), scheme_(scheme) {}

  const SpanImage* run(const SpanImage* spans, const std::string& failure,
                       Recorder& recorder) override;

 private:
  // The merged bands this rank holds after the exchange.
  std::vector<std::byte> merge(const SpanImage& local, Recorder& recorder);
  // Every rank's failure or none: throws naming the first rank that failed.
  void agree(bool ok, const std::string& failure);
  // The exchange and merge of `local`; true on the root, whose composite_ then holds the
  // composite. composite.bytes_sent counts from `bytes_before`.
  bool composite(const SpanImage& local, std::int64_t bytes_before, Recorder& recorder);

  Communicator& comm_;
  const MergeSettings settings_;
  const CompositeScheme scheme_;
  SpanImage composite_;  // the root's composite
};

}  // namespace voxspan
