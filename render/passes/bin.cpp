#include "render/passes/bin.h"

#include <algorithm>
#include <string>

#include "render/grid_uniforms.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr int kSharedTiles = 1024;  // tallies per work group in shared memory (4 KiB each)
constexpr GLuint kMaxGroups = 65535;
const std::string kShared = "#define BIN_SHARED_TILES " + std::to_string(kSharedTiles) + "\n";

}  // namespace

BinPass::BinPass(const gl::ShaderLibrary& shaders)
    : count_shared_(shaders.compute("render/passes/bin.comp", kShared)),
      scatter_shared_(shaders.compute("render/passes/bin.comp", kShared + "#define BIN_SCATTER 1")),
      count_global_(shaders.compute("render/passes/bin.comp")),
      scatter_global_(shaders.compute("render/passes/bin.comp", "#define BIN_SCATTER 1")) {}

const std::vector<std::uint32_t>& BinPass::run(const gl::Buffer& particles, std::size_t count,
                                               const PerspectiveGrid& grid,
                                               const TileLayout& tiles, PrefixSumPass& prefix_sum) {
  const std::size_t tile_count = static_cast<std::size_t>(tiles.count());
  const bool shared = tile_count <= std::size_t(kSharedTiles);
  const gl::Program& count_pass = shared ? count_shared_ : count_global_;
  const gl::Program& scatter_pass = shared ? scatter_shared_ : scatter_global_;
  const auto groups = static_cast<GLuint>(std::clamp<std::size_t>((count + 255) / 256, 1, kMaxGroups));
  for (const gl::Program* p : {&count_pass, &scatter_pass}) {
    set_grid_uniforms(*p, grid);
    p->set("u_count", static_cast<unsigned>(count));
    p->set("u_tile_size", glm::ivec2(tiles.tile_width, tiles.tile_height));
    p->set("u_tiles", glm::ivec2(tiles.columns, tiles.rows));
  }
  counts_.reserve((tile_count + 1) * 4);
  counts_.clear(0, (tile_count + 1) * 4);
  particles.bind(GL_SHADER_STORAGE_BUFFER, 0);
  counts_.bind(GL_SHADER_STORAGE_BUFFER, 1);
  count_pass.dispatch(groups);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  prefix_sum.run(counts_, tile_count);
  offsets_ = counts_.read<std::uint32_t>(tile_count + 1);
  // The scatter turns each tile's first slot into a cursor.
  lists_.reserve(std::max<std::size_t>(offsets_.back(), 1) * 4);
  particles.bind(GL_SHADER_STORAGE_BUFFER, 0);
  counts_.bind(GL_SHADER_STORAGE_BUFFER, 1);
  lists_.bind(GL_SHADER_STORAGE_BUFFER, 2);
  scatter_pass.dispatch(groups);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  return offsets_;
}

}  // namespace voxspan
