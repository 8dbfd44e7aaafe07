// insitu/parallel/span_merge.h - exact compositing of span images (render/span_image.h) made by
// several ranks in the same perspective grid: per pixel, the union of every rank's intervals,
// then gap bridging again (the compress pass's rule, [ZD15] sec. 3.2, 4.4: a gap closes when
// it is shorter than g along the ray, measured between the centres of the voxels on either
// side; between the depths themselves for the CPU renderer's exact spans), then the span cap
// (sec. 3.1). Union is idempotent, so a ghost particle voxelized on
// two ranks does no harm, and the result does not depend on how the fluid was split: the spans
// are those one rank would find from the union of the bit columns. A pixel that only one rank
// saw keeps that rank's record as it is (bit for bit); a merged one gets its `inside` summed
// again, in double precision as the exact reference does.
//
// Bands of rows travel as bytes: for every pixel of the band with spans, its index in the
// image, its total and count (uint32), its inside (float) and its spans (float pairs).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "render/span_image.h"

namespace voxspan {

struct MergeSettings {
  double gap_bridging = 0;      // g, world units along the ray; 0: no bridging
  std::uint32_t max_spans = 0;  // cap on stored spans per pixel after the merge; 0: none
  // The spans are exact (the CPU renderer's, render/cpu/span_caster.h): a gap closes when the
  // distance between the depths themselves is shorter than g, as the caster decides it,
  // rather than between voxel centres.
  bool exact_depths = false;
};

// Rows [row_begin, row_end) of `image` (its pixels with spans only).
std::vector<std::byte> encode_rows(const SpanImage& image, int row_begin, int row_end);

// The union of the encoded bands `parts` (one per rank, any subset of the rows), merged as
// above, encoded the same way.
std::vector<std::byte> merge_rows(const PerspectiveGrid& grid,
                                  std::span<const std::vector<std::byte>> parts,
                                  const MergeSettings& settings);

// The span image of `grid` that holds the encoded bands (pixels in none are empty).
SpanImage decode_image(const PerspectiveGrid& grid, std::span<const std::vector<std::byte>> bands);
// The same into `out`, keeping its memory (once a frame in an MPI job).
void decode_image(const PerspectiveGrid& grid, std::span<const std::vector<std::byte>> bands,
                  SpanImage& out);

// The rows rank `rank` of `ranks` merges: an equal share of the image's rows, in order.
struct RowBand {
  int begin = 0, end = 0;
};
RowBand band_of(int rank, int ranks, int height);

}  // namespace voxspan
