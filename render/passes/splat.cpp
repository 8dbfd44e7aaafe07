#include "render/passes/splat.h"

#include <algorithm>

#include "render/grid_uniforms.h"

namespace voxspan {
namespace {
constexpr GLuint kMaxGroups = 65535;
}

SplatPass::SplatPass(const gl::ShaderLibrary& shaders) {
  for (int list = 0; list < 2; ++list)
    for (int per_pixel = 0; per_pixel < 2; ++per_pixel) {
      std::string defines;
      if (list) defines += "#define SPLAT_FROM_LIST 1\n";
      if (per_pixel) defines += "#define SPLAT_PER_PIXEL 1\n";
      programs_[list][per_pixel] = shaders.compute("render/passes/splat.comp", defines);
    }
}

void SplatPass::run(const gl::Buffer& bits, const SplatInput& input, const PerspectiveGrid& grid,
                    const TileLayout& layout, const TileRect& tile,
                    const SplatSettings& settings) const {
  const bool from_list = input.list != nullptr;
  const std::uint32_t count = from_list ? input.list_count : input.particle_count;
  if (count == 0) return;
  const gl::Program& p =
      programs_[from_list ? 1 : 0][settings.threads == SplatThreads::per_pixel ? 1 : 0];
  set_grid_uniforms(p, grid);
  p.set("u_chunks", static_cast<unsigned>(layout.column_bytes / 16));
  p.set("u_tile_pixels", static_cast<unsigned>(tile.pixels()));
  p.set("u_tile", glm::ivec4(tile.x0, tile.y0, tile.width, tile.height));
  p.set("u_count", count);
  p.set("u_list_offset", input.list_offset);
  p.set("u_gap", float(settings.gap_bridging));
  p.set("u_surface_only", settings.surface_only && settings.gap_bridging > 0 ? 1u : 0u);
  bits.bind_range(GL_SHADER_STORAGE_BUFFER, 0, 0, layout.column_bytes * tile.pixels());
  input.particles->bind(GL_SHADER_STORAGE_BUFFER, 1);
  if (from_list) input.list->bind(GL_SHADER_STORAGE_BUFFER, 2);
  p.dispatch(static_cast<GLuint>(std::min<std::uint32_t>(kMaxGroups, (count + 63) / 64)));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace voxspan
