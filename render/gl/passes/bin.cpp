#include "render/gl/passes/bin.h"

#include <algorithm>
#include <string>

#include "render/gl/info.h"
#include "render/gl/passes/depth_bounds.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {

constexpr int kSharedTiles = 1024;  // tallies per work group in shared memory (4 KiB each)
constexpr GLbitfield kBarriers = GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;

enum Binding : GLuint { kParticles, kTileCounts, kTileLists, kLarge, kLargeList, kDepthBounds };

}  // namespace

BinPass::BinPass(const gl::ShaderLibrary& shaders)
    : automatic_(gl::software_renderer() ? BinTallies::global : BinTallies::shared) {
  const std::string bindings = gl::defines({{"PARTICLES_BINDING", kParticles},
                                            {"TILE_COUNTS_BINDING", kTileCounts},
                                            {"TILE_LISTS_BINDING", kTileLists},
                                            {"LARGE_BINDING", kLarge},
                                            {"LARGE_LIST_BINDING", kLargeList},
                                            {"DEPTH_BOUNDS_BINDING", kDepthBounds}});
  const std::string variant[3] = {"#define BIN_LARGE_ONLY 1\n", "",
                                  gl::defines({{"BIN_SHARED_TILES", kSharedTiles}})};
  for (int v = 0; v < 3; ++v)
    for (int scatter = 0; scatter < 2; ++scatter)
      programs_[v][scatter] =
          shaders.compute("render/gl/passes/bin.comp",
                          bindings + variant[v] + (scatter ? "#define BIN_SCATTER 1" : ""));
}

const Bins& BinPass::run(const gl::Buffer& particles, std::size_t count,
                         const PerspectiveGrid& grid, const TileLayout& tiles,
                         PrefixSumPass& prefix_sum, bool tile_lists, BinTallies tallies,
                         std::span<const std::uint32_t> seed_bounds) {
  const std::size_t tile_count = static_cast<std::size_t>(tiles.count());
  if (tallies == BinTallies::automatic) tallies = automatic_;
  const bool shared = tallies == BinTallies::shared && tile_count <= std::size_t(kSharedTiles);
  const int variant = !tile_lists ? 0 : (shared ? 2 : 1);
  const gl::Program& count_pass = programs_[variant][0];
  const gl::Program& scatter_pass = programs_[variant][1];
  for (const gl::Program* p : {&count_pass, &scatter_pass}) {
    set_grid_uniforms(*p, grid);
    p->set("u_count", static_cast<unsigned>(count));
    p->set("u_tile_size", glm::ivec2(tiles.tile_width, tiles.tile_height));
    p->set("u_tiles", glm::ivec2(tiles.columns, tiles.rows));
    set_depth_block_uniforms(*p, grid);
  }
  const auto bind_all = [&] {
    gl::bind_storage({{particles, kParticles},
                      {counts_, kTileCounts},
                      {lists_, kTileLists},
                      {large_, kLarge},
                      {large_list_, kLargeList},
                      {depth_bounds_, kDepthBounds}});
  };
  counts_.reserve((tile_count + 1) * 4);
  counts_.clear(0, (tile_count + 1) * 4);
  large_.reserve(8);
  large_.clear(0, 8);
  const std::size_t bounds_bytes = (depth_block_count(grid) + 1) * 8;
  depth_bounds_.reserve(bounds_bytes);
  if (seed_bounds.size_bytes() == bounds_bytes)
    depth_bounds_.upload(seed_bounds.data(), bounds_bytes);
  else depth_bounds_.clear(0, bounds_bytes);
  lists_.reserve(4);
  large_list_.reserve(4);
  bind_all();
  dispatch_strided(count_pass, count);
  glMemoryBarrier(kBarriers);

  bins_.offsets.clear();
  if (tile_lists) {
    prefix_sum.run(counts_, tile_count);
    bins_.offsets.resize(tile_count + 1);  // keeps its storage from frame to frame
    counts_.download(bins_.offsets.data(), bins_.offsets.size() * sizeof(std::uint32_t));
  }
  bins_.large = large_.read_array<std::uint32_t, 1>()[0];
  // The scatter turns each tile's first slot into a cursor.
  lists_.reserve(std::max<std::size_t>(tile_lists ? bins_.offsets.back() : 0, 1) * 4);
  large_list_.reserve(std::max<std::size_t>(bins_.large, 1) * 4);
  bind_all();
  dispatch_strided(scatter_pass, count);
  glMemoryBarrier(kBarriers);
  return bins_;
}

}  // namespace voxspan
