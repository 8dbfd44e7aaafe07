// render/voxelizer.h - the voxelization stage of [ZD15] (sec. 3.1, 3.2, 4.1-4.4) from
// boundary particles and cell states to the span image, on the GPU, tile by tile:
//   frame (CPU): fit the perspective grid to the visible particles, count what is culled;
//   upload: the particles (zero-copy layout) and the cell states;
//   bin: particles into the tiles they touch, once (or not at all: Binning::resplat_all);
//   per tile: clear the bits that can hold fluid, splat, compress into the span image.
// Every pass is timed through the caller's gl::PassTimer and reports its counts into FrameStats.
#pragma once

#include <cstdint>
#include <span>

#include "render/cell_state_texture.h"
#include "render/frame_stats.h"
#include "render/gl/pass_timer.h"
#include "render/gl/shader_library.h"
#include "render/gpu_span_image.h"
#include "render/passes/bin.h"
#include "render/passes/clear.h"
#include "render/passes/clear_columns.h"
#include "render/passes/compress.h"
#include "render/passes/prefix_sum.h"
#include "render/passes/splat.h"
#include "render/perspective_grid.h"
#include "render/tiling.h"
#include "voxspan/cell_states.h"

namespace voxspan {

enum class Binning {
  per_tile_lists,  // bin once per frame; each tile splats only its own particles
  resplat_all,     // the paper's way: every particle is splatted for every tile
};

struct VoxelizeOptions {
  GridOptions grid;
  TileOptions tiles;
  double gap_bridging = 0;      // g: gaps shorter than this along the ray close (world units)
  bool surface_splat = true;    // with g > 0, mark only entry/exit voxels where 2 r < g
  std::uint32_t max_spans = 0;  // cap on stored spans per pixel (sec. 3.1); 0 = no cap
  int scratch_spans = 8;        // spans per pixel the compress pass keeps between its passes
  // Where a span's entry and exit lie in the voxels that end it (the CPU renderer's are exact).
  // Centres are closer to the exact pictures (docs/results.md), but spans of two ranks that
  // meet in one voxel run then leave a voxel's gap between them: compositing stays exact with
  // the faces only, so they are the default.
  SpanEdges span_edges = SpanEdges::outer;
  bool use_cell_states = true;  // skip inner-empty, fill inner-full cells (sec. 4.3)
  Binning binning = Binning::per_tile_lists;
  SplatThreads splat_threads = SplatThreads::automatic;
  BinTallies bin_tallies = BinTallies::automatic;
  // The other processes voxelizing into the same grid (PerspectiveGrid::fit); empty: none.
  // With them, this process's inner-full cells need not lie between its own boundary
  // particles (another rank may hold the fluid's far side), so the compress pass's depth
  // bounds take the cells in too (inner_full_depth_bounds).
  DepthRangeCombine combine_ranks;
};

// Throws voxspan::Error naming the option that is out of range.
void validate(const VoxelizeOptions& options);

// A frame's perspective grid, fitted to the particles the camera sees (options.grid,
// options.combine_ranks), timed as "frame", with its counts and figures (particles.*, grid.*)
// in `stats`: the first step of both renderers. Throws voxspan::Error (its stats filled in)
// when the visible particles reach past 1e18 world units from the eye: the passes after it
// work in float, whose squares of lengths overflow there.
PerspectiveGrid fit_frame(const Camera& camera, std::span<const ParticleSphere> particles,
                          const VoxelizeOptions& options, gl::PassTimer& timer, FrameStats& stats);

class Voxelizer {
 public:
  // Needs a current GL context; compiles the passes.
  explicit Voxelizer(const gl::ShaderLibrary& shaders);

  // Voxelizes one frame. The result stays valid until the next run(). Throws voxspan::Error on
  // bad options, a budget too small for one tile row, or a frame deeper than fit_frame takes;
  // bad particles (NaN, radius <= 0) are counted and skipped, never an error.
  const GpuSpanImage& run(const Camera& camera, std::span<const ParticleSphere> particles,
                          const CellStatesView& cells, const VoxelizeOptions& options,
                          gl::PassTimer& timer, FrameStats& stats);

  const GpuSpanImage& image() const { return image_; }
  // Largest bytes one shader-storage binding may hold here: min(GL limit, 1 GiB).
  std::size_t max_binding_bytes() const { return max_binding_; }

 private:
  std::size_t max_binding_ = 0;
  ClearPass clear_;  // the span image's pixel records
  ClearColumnsPass clear_columns_;
  PrefixSumPass prefix_sum_;
  BinPass bin_;
  SplatPass splat_;
  CompressPass compress_;
  CellStateTexture cells_;
  gl::Buffer particles_;
  gl::Buffer bits_;
  GpuSpanImage image_;
};

}  // namespace voxspan
