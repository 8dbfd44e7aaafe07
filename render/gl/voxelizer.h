// render/gl/voxelizer.h - the voxelization stage of [ZD15] (sec. 3.1, 3.2, 4.1-4.4) from
// boundary particles and cell states to the span image, on the GPU, tile by tile:
//   frame (CPU): fit the perspective grid to the visible particles, count what is culled;
//   upload: the particles (zero-copy layout) and the cell states;
//   bin: particles into the tiles they touch, once (or not at all: Binning::resplat_all);
//   per tile: clear the bits that can hold fluid, splat, compress into the span image.
// Every pass is timed and counted through the caller's Recorder (render/stat_names.h).
#pragma once

#include <cstdint>
#include <span>

#include "render/frame.h"
#include "render/gl/cell_state_texture.h"
#include "render/gl/gpu_span_image.h"
#include "render/gl/passes/bin.h"
#include "render/gl/passes/clear.h"
#include "render/gl/passes/clear_columns.h"
#include "render/gl/passes/compress.h"
#include "render/gl/passes/prefix_sum.h"
#include "render/gl/passes/splat.h"
#include "render/gl/shader_library.h"
#include "render/gl/tiling.h"
#include "render/perspective_grid.h"
#include "voxspan/cell_states.h"

namespace voxspan {

enum class Binning {
  per_tile_lists,  // bin once per frame; each tile splats only its own particles
  resplat_all,     // the paper's way: every particle is splatted for every tile
};

// SpanOptions (render/frame.h) and how the GL passes work. With other ranks
// (SpanOptions::combine_ranks) the compress pass's depth bounds take this process's inner-full
// cells in too (inner_full_depth_bounds): they need not lie between its own boundary particles.
struct VoxelizeOptions : SpanOptions {
  TileOptions tiles;
  bool surface_splat = true;  // with g > 0, mark only entry/exit voxels where 2 r < g
  int scratch_spans = 8;      // spans per pixel the compress pass keeps between its passes
  // Where a span's entry and exit lie in the voxels that end it (the CPU renderer's are exact).
  // Centres are closer to the exact pictures (docs/results.md), but spans of two ranks that
  // meet in one voxel run then leave a voxel's gap between them: compositing stays exact with
  // the faces only, so they are the default.
  SpanEdges span_edges = SpanEdges::outer;
  Binning binning = Binning::per_tile_lists;
  SplatThreads splat_threads = SplatThreads::automatic;
  BinTallies bin_tallies = BinTallies::automatic;
};

// Throws voxspan::Error naming the option that is out of range.
void validate(const VoxelizeOptions& options);

class Voxelizer {
 public:
  // Needs a current GL context; compiles the passes.
  explicit Voxelizer(const gl::ShaderLibrary& shaders);

  // Voxelizes one frame. The result stays valid until the next run(). Throws voxspan::Error on
  // bad options, a budget too small for one tile row, or a frame deeper than fit_frame takes;
  // bad particles (NaN, radius <= 0) are counted and skipped, never an error.
  const GpuSpanImage& run(const Camera& camera, std::span<const ParticleSphere> particles,
                          const CellStatesView& cells, const VoxelizeOptions& options,
                          Recorder& recorder);

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
