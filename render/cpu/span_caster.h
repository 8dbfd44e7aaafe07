// render/cpu/span_caster.h - the CPU renderer's span image: exact spans by casting each pixel's
// centre ray against the boundary spheres (analytic chords) and the inner-full cells (boxes),
// no bit grid and no layers. The rules are the voxelization's ([ZD15] sec. 3.1, 3.2, 4.3,
// 4.4): the union of the intervals, clipped to the grid's [near, grid_far]; gaps shorter than
// the gap-bridging distance along the ray closed; inner-full cells counted as fluid; the span
// cap applied by SpanListBuilder. The answer is the exact reference's
// (render/reference/exact_spans.h) up to rounding at cell faces and in the chords' centres:
// the two share no code but the list rule, and the tests hold them to each other.
//
// Work, in the phases of CastPhase below (each timed: CastCounts::phase_ms): screen tiles of
// kTile^2 pixels in parallel (oneTBB); each tile walks the spheres (nearest first, packed per
// tile) and cell boxes whose pixel rectangles touch it, sphere by sphere over the pixels it
// covers, so the cost follows the spheres' footprints, not pixels x candidates; each chord joins
// its pixel's union at once (most only move its last exit, and those inside it are found without
// a square root).
// Inner-full cells go in merged into few boxes. Memory: the spans and one union per pixel of
// the tiles in flight; tiles join in their order, so the image does not depend on the threads.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "render/perspective_grid.h"
#include "render/span_image.h"
#include "voxspan/cell_states.h"

namespace voxspan {

struct CastSettings {
  double gap_bridging = 0;      // world units along the ray
  std::uint32_t max_spans = 0;  // stored spans per pixel; 0 = no cap
  bool use_cell_states = true;  // inner-full cells count as fluid
};

// The phases of SpanCaster::run, in the order they run; kCastPhaseNames[p] names phase p.
//   project     the spheres to view space and the inner-full cells to merged boxes, each with
//               the pixels it may cover
//   sort        the spheres in view nearest first (a counting sort on depth)
//   bin         the spheres and boxes into the screen tiles their pixels touch
//   cast_tiles  per tile, each pixel's union of chords and the tile's spans from the unions
//   join        the tiles' spans into the span image, in tile order
enum class CastPhase { project, sort, bin, cast_tiles, join };
inline constexpr std::array<const char*, 5> kCastPhaseNames{"project", "sort", "bin", "cast_tiles",
                                                            "join"};
static_assert(kCastPhaseNames.size() == std::size_t(CastPhase::join) + 1);

struct CastCounts {
  std::int64_t spheres = 0;      // in view, binned
  std::int64_t cell_boxes = 0;   // runs of inner-full cells in view
  std::int64_t chord_tests = 0;  // sphere-pixel pairs tried
  std::int64_t tiles = 0;
  std::int64_t spans_found = 0;    // SpanImage::total_spans(), counted on the way
  std::int64_t capped_pixels = 0;  // SpanImage::capped_pixels()
  // Wall time of each phase, milliseconds, by CastPhase (all 0 for an empty grid).
  std::array<double, kCastPhaseNames.size()> phase_ms{};
};

class SpanCaster {
 public:
  // Screen tile side, pixels: each tile a sphere touches walks it again, so larger tiles walk
  // it fewer times (32 against 16: the step 1.7 ms faster at 100 k particles, 640x360,
  // docs/benchmarks.md). 64 was 0.5 ms faster still on two cores, but leaves 60 tiles at
  // 640x360, which would leave many cores idle (reasoned, not measured).
  static constexpr int kTile = 32;

  SpanCaster();
  ~SpanCaster();
  SpanCaster(SpanCaster&&) noexcept;
  SpanCaster& operator=(SpanCaster&&) noexcept;

  // The spans of `particles` and `cells` in `grid`, into `out` (its storage reused).
  CastCounts run(const PerspectiveGrid& grid, std::span<const ParticleSphere> particles,
                 const CellStatesView& cells, const CastSettings& settings, SpanImage& out);

 private:
  struct Work;
  std::unique_ptr<Work> work_;  // bins and per-thread lists, kept from frame to frame
};

}  // namespace voxspan
