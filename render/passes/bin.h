// render/passes/bin.h - bins particles into the screen tiles their spheres touch, once per frame
// (render/passes/bin.comp): count, prefix sum, scatter, all on the GPU. Each tile then splats
// only its own list, instead of every particle (the paper's way, sec. 3.1).
// Reads: the particle buffer. Writes: lists() and the per-tile offsets into it.
// Cost: two passes over the particles; one small read-back (tiles + 1 uints) to size the lists.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/gl/objects.h"
#include "render/gl/shader_library.h"
#include "render/passes/prefix_sum.h"
#include "render/perspective_grid.h"
#include "render/tiling.h"

namespace voxspan {

class BinPass {
 public:
  explicit BinPass(const gl::ShaderLibrary& shaders);
  // Returns the offsets of the tiles' lists: tile t owns lists()[offsets[t], offsets[t + 1]).
  const std::vector<std::uint32_t>& run(const gl::Buffer& particles, std::size_t count,
                                        const PerspectiveGrid& grid, const TileLayout& tiles,
                                        PrefixSumPass& prefix_sum);
  const gl::Buffer& lists() const { return lists_; }

 private:
  gl::Program count_shared_, scatter_shared_, count_global_, scatter_global_;
  gl::Buffer counts_;
  gl::Buffer lists_;
  std::vector<std::uint32_t> offsets_;
};

}  // namespace voxspan
