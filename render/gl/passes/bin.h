// render/gl/passes/bin.h - bins particles into the screen tiles their spheres touch, once per frame
// (render/gl/passes/bin.comp): count, prefix sum, scatter, all on the GPU. Each tile then splats
// only its own list, instead of every particle (the paper's way, sec. 3.1). Large spheres
// (render/gl/passes/sphere_work.glsl) go to a list of their own for splat_large.comp; with
// tile_lists off (the paper's re-splat mode) only that list is made. The count pass also gathers
// the depth range of each 16x16-pixel block (render/gl/passes/depth_bounds.glsl) for compress.
// Reads: the particle buffer. Writes: lists(), large_list(), depth_bounds(), tile offsets.
// Cost: two passes over the particles; one small read-back (tiles + 2 uints) to size the lists.
// Tallies go through shared memory on GPUs and straight to global atomics on llvmpipe.
#pragma once

#include <span>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/gl/objects.h"
#include "render/gl/passes/prefix_sum.h"
#include "render/gl/shader_library.h"
#include "render/gl/tiling.h"
#include "render/perspective_grid.h"

namespace voxspan {

// Where the binning tallies (sphere, tile) pairs before the global counters.
enum class BinTallies {
  automatic,  // shared on GPUs, global on llvmpipe (twice as fast there: its barriers are slow)
  shared,     // per work group in shared memory, one global atomic per (group, tile)
  global,     // one global atomic per (sphere, tile)
};

struct Bins {
  // Tile t owns lists()[offsets[t], offsets[t + 1]); empty without tile lists.
  std::vector<std::uint32_t> offsets;
  std::uint32_t large = 0;  // entries of large_list()
};

class BinPass {
 public:
  explicit BinPass(const gl::ShaderLibrary& shaders);
  // `seed_bounds`: depth bounds the blocks start from (inner_full_depth_bounds(), in the
  // buffer's layout); empty: none, they grow from zero.
  const Bins& run(const gl::Buffer& particles, std::size_t count, const PerspectiveGrid& grid,
                  const TileLayout& tiles, PrefixSumPass& prefix_sum, bool tile_lists,
                  BinTallies tallies = BinTallies::automatic,
                  std::span<const std::uint32_t> seed_bounds = {});
  const gl::Buffer& lists() const { return lists_; }
  const gl::Buffer& large_list() const { return large_list_; }
  const gl::Buffer& depth_bounds() const { return depth_bounds_; }

 private:
  // [tile lists: 0 = large only, 1 = global atomics, 2 = shared tallies][scatter]
  gl::Program programs_[3][2];
  gl::Buffer counts_, lists_, large_, large_list_, depth_bounds_;
  BinTallies automatic_ = BinTallies::shared;
  Bins bins_;
};

}  // namespace voxspan
