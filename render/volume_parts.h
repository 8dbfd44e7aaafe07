// render/volume_parts.h - a volume frame (render/volume.h) cast by several ranks, each over its
// own particles, and merged so that the picture is the one a single process makes from all of
// them, up to rounding, however the particles were split and with no ghost layer assumed. The
// ranks' pictures cannot simply be composited: the transfer function is not linear in the
// field, so a sample that two ranks' particles reach must be summed before it is looked up.
//
// Per pixel, on the lattice's sample indices:
//   1. cover: each rank finds the hull [first, last] of the samples its supports reach;
//   2. the samples inside two or more ranks' hulls are shared (shared_ranges()): each rank sends
//      its sums there (RawSample), and composites the runs of samples only it reaches into
//      segments (PartSegment: light and transmittance from a transmittance of 1, its own iso hits
//      lit), which hold nothing another rank could change;
//   3. the merge (render/volume_merge.h) sums the shared samples, composites them and the
//      segments front to back, and finds the iso crossings between them; those it lights with
//      the field's sums every rank adds at them (HitQuery -> FieldSums).
// insitu/parallel/volume_exchange.h moves these between MPI ranks.
//
// What is not the single process's to rounding: with early termination on, a segment stops on
// its own transmittance and the merge on the whole ray's, so they may differ by at most
// `termination` of the light behind the stop (exact with termination 0); a ray with more than
// model::kMaxIsoHits iso hits may light different ones; the depth output's point of opacity 0.5
// inside a segment that starts behind other fluid is the segment's own (its iso hits are exact).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace voxspan {

// Sample indices first..last of the lattice (VolumeLattice::depth); empty when last < first.
struct SampleRange {
  std::int32_t first = 0, last = -1;
  bool empty() const { return last < first; }
};

// Per pixel (x + y * width) a sorted list of disjoint ranges.
struct PixelRanges {
  std::vector<std::uint32_t> start;  // pixels + 1 offsets into `ranges`
  std::vector<SampleRange> ranges;
  std::span<const SampleRange> of(std::size_t pixel) const {
    return {ranges.data() + start[pixel], ranges.data() + start[pixel + 1]};
  }
};

// Per rank (in rank order) the samples of its hull `hulls[r]` that other ranks' hulls hold too,
// appended to shared[r].
void shared_ranges(std::span<const SampleRange> hulls,
                   std::vector<std::vector<SampleRange>>& shared);

// One rank's sums at a shared sample.
struct RawSample {
  std::int32_t index;
  double s, w;
};

// A run of samples only one rank reaches, composited there.
struct PartSegment {
  std::int32_t first = 0, last = -1;  // its samples
  float q_first = 0, q_last = 0;      // the values at its ends
  std::uint32_t flags = 0;            // kFirstDefined | kLastDefined | kStopped
  glm::vec3 color{0.0f};              // premultiplied, from transmittance 1; its iso hits lit
  float transmittance = 1;
  float hit_depth = 0;   // distance along the ray to its first iso hit; 0: none
  float half_depth = 0;  // to the sample where its transmittance fell under 0.5; 0: never

  static constexpr std::uint32_t kFirstDefined = 1, kLastDefined = 2;
  static constexpr std::uint32_t kStopped = 4;  // transmittance under `termination`: the ray ends
};

// One rank's part of a frame: per pixel, in sample order, its sums at the shared samples and its
// segments.
struct VolumePart {
  int width = 0, height = 0;
  std::vector<std::uint32_t> raw_start, segment_start;  // pixels + 1 offsets
  std::vector<RawSample> raws;
  std::vector<PartSegment> segments;

  std::span<const RawSample> raws_of(std::size_t pixel) const {
    return {raws.data() + raw_start[pixel], raws.data() + raw_start[pixel + 1]};
  }
  std::span<const PartSegment> segments_of(std::size_t pixel) const {
    return {segments.data() + segment_start[pixel], segments.data() + segment_start[pixel + 1]};
  }
};

// Where the merge wants the field's sums: an iso hit at view depth `depth` on pixel `pixel`'s ray.
struct HitQuery {
  std::uint32_t pixel;
  float depth;
};

}  // namespace voxspan
