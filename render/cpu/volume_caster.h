// render/cpu/volume_caster.h - a volume view's frame on the CPU ([FAW10] sec. 3-5, [HOK16] sec.
// 2, 6): every pixel's ray sampled on the lattice of render/volume.h, each sample the exact SPH
// sum, in double, of the particles whose support holds it, composited front to back by
// render/model/volume.glsl. No grid in memory: the work and the memory follow the particles'
// supports and the pixels.
//
// Phases (VolumeCastPhase, each timed):
//   project  with level of detail first the far particles merged (render/cpu/volume_lod.h);
//            each particle's support to view space: its pixel rectangle and its first and last
//            samples (culled where it reaches no pixel centre or no sample);
//   sort     the supports nearest first (by first sample, then by index: one order whatever the
//            threads);
//   bin      into screen tiles of kTile^2 pixels, the order kept (render/cpu/screen_bins.h);
//   march    per tile, in parallel: the tile's supports in order, each adding its kernel to the
//            samples of the rays it crosses; a ray's samples are composited as soon as no later
//            support can reach them (every later one starts at or after this one's first
//            sample), the ray stops when its transmittance falls under the termination and the
//            tile when all its rays have, a support when all the rays of the bundles it
//            touches have ([FAW10] sec. 5.2's occlusion culling, at tile and bundle grain: every
//            so many samples of depth all the tile's rays are composited up to the next support,
//            so that the opaque ones are seen; the supports behind are not walked, here nor for
//            the iso hits' light, and counted); then the iso hits' gradients from the same
//            supports, the hits lit, and the background behind what is left of each ray's
//            transmittance.
//            With adaptive sampling (render/cpu/volume_adaptive.h) a support whose samples lie in
//            coarse cells of a bundle adds its kernel at the samples those take only, without
//            its chords' ends, one that reaches only super-pixels is not read, and each ray takes
//            its bundle's super-pixels whether a support reached it there or not.
// Each sample's sum adds its particles in the sorted order: the picture does not depend on the
// number of threads. The phases' parts: render/cpu/volume_supports.h (project, sort, bin; a
// support's kernel sums), render/cpu/volume_march.h (a tile's supports into its rays) and
// render/cpu/volume_rays.h (a tile's rays composited).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "render/camera.h"
#include "render/volume.h"
#include "render/volume_parts.h"

namespace voxspan {

enum class VolumeCastPhase { project, sort, bin, march };
inline constexpr std::array<const char*, 4> kVolumeCastPhaseNames{"project", "sort", "bin",
                                                                  "march"};

// A frame's project, sort and bin as another march reads them (the GL pass,
// render/gl/passes/volume_march.h): the supports in view, nearest first sample first, each as
// std430 lays it out; per screen tile of kTile^2 pixels the positions of its supports in that
// order; the sample depths from `base`.
struct GpuSupport {
  double cx, cy, cz, radius;    // view-space centre, support radius R = kernel support * h
  float inv_h, v, vq, pad0;     // 1 / h, the weight and the weight times the value
  std::int32_t first, last;     // its first and last samples, relative to `base`
  std::int32_t x0, y0, x1, y1;  // its pixel rectangle
  std::int32_t pad1, pad2;
};
static_assert(sizeof(GpuSupport) == 80);

// Adaptive sampling's plans (render/cpu/volume_adaptive.h) as another march reads them. A bundle's
// cells run from the cell of its tile's first sample (the first of the tile's list's first
// support) to that of its last.
struct GpuPlans {
  // bundle_cells' mark of a bundle at full rate in every cell (no plan to read); an int, as
  // GLSL's literals are.
  static constexpr std::uint32_t kFullRate = 0x7fffffff;
  // A cell's word: its CellPlan::level in the low kLevelBits, a super-pixel's index in
  // super_pixels above them.
  static constexpr std::uint32_t kLevelBits = 3;

  std::vector<std::uint32_t> bundle_cells;  // per bundle (row-major over the frame): its first cell
  std::vector<std::uint32_t> cells;
  std::vector<std::array<float, 4>> super_pixels;  // light (premultiplied), transmittance
};

struct VolumeSetup {
  std::vector<GpuSupport> supports;
  std::vector<std::uint32_t> tile_start;  // per tile its first entry in tile_lists, then the total
  std::vector<std::uint32_t> tile_lists;
  int tiles_x = 0;  // tiles per row
  std::int64_t base = 0;
  std::vector<double> depths;  // depth of sample base + k
  double near = 0;
  VolumeLattice lattice;
  // Where the options ask for adaptive sampling and it applies (DVR of a Shepard field), the
  // plans, a weight proven at the weight floor with room for float sums' rounding.
  bool adaptive = false;
  GpuPlans plans;
};

// Holds its scratch (supports, bins, per-thread rings) from frame to frame.
class VolumeCaster {
 public:
  static constexpr int kTile = 32;  // as the span caster's (render/cpu/span_caster.h)

  VolumeCaster();
  ~VolumeCaster();
  VolumeCaster(const VolumeCaster&) = delete;
  VolumeCaster& operator=(const VolumeCaster&) = delete;

  // One frame into `out` (its storage reused). Throws voxspan::Error on bad options or camera;
  // bad particles are counted and skipped. phase_ms (when given) gets each phase's wall time.
  VolumeCounts run(const Camera& camera, std::span<const VolumeParticle> particles,
                   const VolumeOptions& options, VolumeFrame& out,
                   std::array<double, kVolumeCastPhaseNames.size()>* phase_ms = nullptr);

  // This rank's part of a frame cast over several ranks (render/volume_parts.h). cover() starts
  // the frame as run() does and gives per pixel the hull of the samples these particles reach;
  // run_part() marches it given the samples other ranks reach too (`shared`, per pixel), into
  // `out` (adaptive sampling with options.adaptive.share of the tolerance, the cells holding
  // shared samples at full rate); field_sums() adds these particles' sums at the merge's iso hits
  // (appended to `out`, one per query). The last two read the frame cover() started.
  VolumeCounts cover(const Camera& camera, std::span<const VolumeParticle> particles,
                     const VolumeOptions& options, std::vector<SampleRange>& hulls);
  VolumeCounts run_part(const PixelRanges& shared, VolumePart& out);
  void field_sums(std::span<const HitQuery> queries, std::vector<FieldSums>& out) const;

  // Whether supports behind opaque tiles and bundles are left out (default: yes). Off, every
  // ray still stops on its own and the picture is the same bit for bit: a switch for tests and
  // benchmarks.
  void set_tile_culling(bool on);

  // The frame run() would march, for another march summing in float (`out`'s storage reused);
  // the counts include the plans' cells.
  VolumeCounts setup(const Camera& camera, std::span<const VolumeParticle> particles,
                     const VolumeOptions& options, VolumeSetup& out);

 private:
  struct Work;
  std::unique_ptr<Work> work_;

  // validate, project, sort, bin: the frame every mode marches; `lap` times each phase.
  template <class Lap>
  VolumeCounts start_frame(const Camera& camera, std::span<const VolumeParticle> particles,
                           const VolumeOptions& options, Lap&& lap);
};

}  // namespace voxspan
