// render/gl/passes/splat.h - marks the voxels of one tile that the particle spheres cover
// (render/gl/passes/splat.comp; [ZD15] sec. 3.1, 4.1, 4.4).
// Reads: particles (vec4), the tile's list from BinPass, or every particle (the paper's way),
// and the large spheres' list. Writes: the tile's bits (layout render/gl/passes/bits.glsl), atomic
// OR. Small spheres are splatted by splat.comp, large ones (render/gl/passes/sphere_work.glsl) by
// splat_large.comp, cut into items so that no thread's loop runs long.
// Cost: one ray-sphere test per (sphere, pixel) of its footprint in the tile and one atomic per
// 32-bit word its chord touches (two words per sphere and pixel with surface-only marking); for
// large spheres a prefix sum over them and a 4-byte read-back.
#pragma once

#include <cstdint>

#include "render/gl/objects.h"
#include "render/gl/passes/prefix_sum.h"
#include "render/gl/shader_library.h"
#include "render/gl/tiling.h"
#include "render/perspective_grid.h"

namespace voxspan {

// How the splat spreads small spheres over threads (measured in docs/benchmarks.md).
enum class SplatThreads {
  // per_particle on llvmpipe (4x faster there: its work-group barriers are slow), per_pixel on
  // GPUs (GPU-NOTES: 9.3 against 13.5 ms on an H100 for sorted particles).
  automatic,
  per_pixel,  // a work group shares 64 spheres' pixels out evenly: one thread per (sphere, pixel)
  per_particle,  // one thread per sphere loops over its pixels
};

struct SplatInput {
  const gl::Buffer* particles = nullptr;
  std::uint32_t particle_count = 0;  // all particles (list == nullptr)
  const gl::Buffer* list = nullptr;  // the tile's small-sphere indices, or nullptr for all
  std::uint32_t list_offset = 0, list_count = 0;
  const gl::Buffer* large_list = nullptr;  // the frame's large-sphere indices
  std::uint32_t large_count = 0;
};

struct SplatSettings {
  double gap_bridging = 0;   // g, world units
  bool surface_only = true;  // with g > 0: entry and exit voxels only for spheres with 2 r < g
  SplatThreads threads = SplatThreads::automatic;
};

class SplatPass {
 public:
  explicit SplatPass(const gl::ShaderLibrary& shaders);
  // What SplatThreads::automatic picks on this GL.
  SplatThreads automatic_threads() const { return automatic_; }
  void run(const gl::Buffer& bits, const SplatInput& input, const PerspectiveGrid& grid,
           const TileLayout& layout, const TileRect& tile, const SplatSettings& settings,
           PrefixSumPass& prefix_sum);

 private:
  void set_uniforms(const gl::Program& p, const PerspectiveGrid& grid, const TileLayout& layout,
                    const TileRect& tile, const SplatSettings& settings) const;
  void run_large(const gl::Buffer& bits, const SplatInput& input, const PerspectiveGrid& grid,
                 const TileLayout& layout, const TileRect& tile, const SplatSettings& settings,
                 PrefixSumPass& prefix_sum);

  // [from list][per pixel]
  gl::Program programs_[2][2];
  SplatThreads automatic_ = SplatThreads::per_pixel;
  gl::Program large_items_, large_splat_;
  gl::Buffer items_;
};

}  // namespace voxspan
