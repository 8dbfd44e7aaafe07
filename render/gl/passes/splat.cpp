#include "render/gl/passes/splat.h"

#include <algorithm>
#include <string>

#include "render/gl/info.h"
#include "render/gl/passes/bits.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {

constexpr const char* kLargeShader = "render/gl/passes/splat_large.comp";

// Bindings of splat.comp and splat_large.comp; `kList`: the tile's list or the large list.
enum Binding : GLuint { kBits, kParticles, kList, kItems };

std::string binding_defines() {
  return gl::defines({{"BITS_BINDING", kBits},
                      {"PARTICLES_BINDING", kParticles},
                      {"LIST_BINDING", kList},
                      {"ITEMS_BINDING", kItems}});
}

}  // namespace

SplatPass::SplatPass(const gl::ShaderLibrary& shaders)
    : large_items_(shaders.compute(kLargeShader, binding_defines() + "#define LARGE_ITEMS 1")),
      large_splat_(shaders.compute(kLargeShader, binding_defines())) {
  for (int list = 0; list < 2; ++list)
    for (int per_pixel = 0; per_pixel < 2; ++per_pixel) {
      std::string defines = binding_defines();
      if (list) defines += "#define SPLAT_FROM_LIST 1\n";
      if (per_pixel) defines += "#define SPLAT_PER_PIXEL 1\n";
      programs_[list][per_pixel] = shaders.compute("render/gl/passes/splat.comp", defines);
    }
  if (gl::software_renderer()) automatic_ = SplatThreads::per_particle;
}

void SplatPass::set_uniforms(const gl::Program& p, const PerspectiveGrid& grid,
                             const TileLayout& layout, const TileRect& tile,
                             const SplatSettings& settings) const {
  set_grid_uniforms(p, grid);
  set_bit_uniforms(p, layout, tile);
  p.set("u_gap", float(settings.gap_bridging));
  p.set("u_surface_only", settings.surface_only && settings.gap_bridging > 0 ? 1u : 0u);
}

void SplatPass::run(const gl::Buffer& bits, const SplatInput& input, const PerspectiveGrid& grid,
                    const TileLayout& layout, const TileRect& tile, const SplatSettings& settings,
                    PrefixSumPass& prefix_sum) {
  bits.bind_range(GL_SHADER_STORAGE_BUFFER, kBits, 0, layout.column_bytes * tile.pixels());
  const bool from_list = input.list != nullptr;
  const std::uint32_t count = from_list ? input.list_count : input.particle_count;
  if (count != 0) {
    const SplatThreads threads =
        settings.threads == SplatThreads::automatic ? automatic_ : settings.threads;
    const gl::Program& p = programs_[from_list ? 1 : 0][threads == SplatThreads::per_pixel ? 1 : 0];
    set_uniforms(p, grid, layout, tile, settings);
    p.set("u_count", count);
    p.set("u_list_offset", input.list_offset);
    input.particles->bind(GL_SHADER_STORAGE_BUFFER, kParticles);
    if (from_list) input.list->bind(GL_SHADER_STORAGE_BUFFER, kList);
    dispatch_strided(p, count);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  if (input.large_count != 0) run_large(bits, input, grid, layout, tile, settings, prefix_sum);
}

void SplatPass::run_large(const gl::Buffer& bits, const SplatInput& input,
                          const PerspectiveGrid& grid, const TileLayout& layout,
                          const TileRect& tile, const SplatSettings& settings,
                          PrefixSumPass& prefix_sum) {
  // A batch's items (pixels in the tile x blocks of 32 words) must add up to less than 2^32.
  const std::size_t blocks = (std::size_t(grid.words_per_column()) + 2 + 31) / 32;
  const std::size_t batch = std::clamp<std::size_t>(
      (std::size_t(1) << 32) / (std::size_t(tile.pixels()) * blocks + 1), 1, 1 << 16);
  // Items per dispatch: at most 8 per thread of the most groups, so loops stay short.
  const std::size_t items_per_dispatch = strided_threads(large_splat_) * 8;
  items_.reserve((batch + 1) * 4);
  const auto bind_all = [&] {
    bits.bind_range(GL_SHADER_STORAGE_BUFFER, kBits, 0, layout.column_bytes * tile.pixels());
    gl::bind_storage(
        {{*input.particles, kParticles}, {*input.large_list, kList}, {items_, kItems}});
  };
  set_uniforms(large_items_, grid, layout, tile, settings);
  set_uniforms(large_splat_, grid, layout, tile, settings);
  for (std::size_t first = 0; first < input.large_count; first += batch) {
    const auto large =
        static_cast<std::uint32_t>(std::min<std::size_t>(batch, input.large_count - first));
    for (const gl::Program* p : {&large_items_, &large_splat_}) {
      p->set("u_large_first", static_cast<unsigned>(first));
      p->set("u_large", large);
    }
    bind_all();
    dispatch_strided(large_items_, large);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    prefix_sum.run(items_, large);
    std::uint32_t total = 0;
    items_.download(&total, 4, std::size_t(large) * 4);
    for (std::size_t item = 0; item < total; item += items_per_dispatch) {
      const auto items = static_cast<std::uint32_t>(std::min(items_per_dispatch, total - item));
      large_splat_.set("u_item_first", static_cast<unsigned>(item));
      large_splat_.set("u_items", items);
      bind_all();
      dispatch_strided(large_splat_, items);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

}  // namespace voxspan
