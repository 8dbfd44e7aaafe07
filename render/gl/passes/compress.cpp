#include "render/gl/passes/compress.h"

#include <string>

#include "render/gl/bindings.h"
#include "render/gl/passes/bits.h"
#include "render/gl/passes/depth_bounds.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {

constexpr const char* kShader = "render/gl/passes/compress.comp";

// compress.comp's own buffers, after the span image's.
enum Binding : GLuint {
  kBits = binding::kSpanImageEnd,
  kScratchSpans,
  kScratchCounts,
  kScratchExits,
  kStats,
  kDepthBounds,
  kRescan,
};

std::string binding_defines() {
  return binding::span_image_defines() + binding::cell_state_defines() +
         gl::defines({{"BITS_BINDING", kBits},
                      {"SCRATCH_SPANS_BINDING", kScratchSpans},
                      {"SCRATCH_COUNTS_BINDING", kScratchCounts},
                      {"SCRATCH_EXITS_BINDING", kScratchExits},
                      {"STATS_BINDING", kStats},
                      {"DEPTH_BOUNDS_BINDING", kDepthBounds},
                      {"RESCAN_BINDING", kRescan}});
}

}  // namespace

CompressPass::CompressPass(const gl::ShaderLibrary& shaders)
    : count_(shaders.compute(kShader, binding_defines())),
      copy_(shaders.compute(kShader, binding_defines() + "#define COMPRESS_COPY 1")),
      rescan_(shaders.compute(kShader, binding_defines() + "#define COMPRESS_RESCAN 1")),
      stats_(16) {}

void CompressPass::begin_frame() { stats_.clear(); }

CompressTallies CompressPass::tallies() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const auto t = stats_.read_array<std::uint32_t, 2>();
  return {t[0], t[1]};
}

void CompressPass::set_uniforms(const gl::Program& p, const TileLayout& layout,
                                const TileRect& tile, const CellStateTexture& cells,
                                const CompressSettings& settings, const GpuSpanImage& image) const {
  set_grid_uniforms(p, image.grid());
  cells.bind(p);
  set_bit_uniforms(p, layout, tile);
  p.set("u_gap", float(settings.gap_bridging));
  p.set("u_center_gap_scale", float(1 + image.grid().k_d() / 2));
  p.set("u_edge_offset", settings.span_edges == SpanEdges::middle ? 0.5f : 0.0f);
  p.set("u_cap", settings.max_spans);
  p.set("u_scratch_spans", static_cast<unsigned>(settings.scratch_spans));
  set_depth_block_uniforms(p, image.grid());
}

std::uint32_t CompressPass::run(const gl::Buffer& bits, const gl::Buffer& depth_bounds,
                                const TileLayout& layout, const TileRect& tile,
                                const CellStateTexture& cells, const CompressSettings& settings,
                                GpuSpanImage& image, std::uint32_t span_base,
                                PrefixSumPass& prefix_sum, std::size_t max_binding_bytes) {
  const auto pixels = static_cast<std::size_t>(tile.pixels());
  // Sized for the largest tile, so the frame's last, smaller tile reallocates nothing.
  const auto most = static_cast<std::size_t>(layout.tile_width) * layout.tile_height;
  scratch_spans_.fit(most * static_cast<std::size_t>(settings.scratch_spans) * 8);
  scratch_counts_.fit((most + 1) * 4);
  scratch_exits_.fit(most * 4);
  rescan_list_.fit((most + 1) * 4);
  rescan_list_.clear(0, 4);
  const auto bind_all = [&] {
    image.bind();
    bits.bind_range(GL_SHADER_STORAGE_BUFFER, kBits, 0, layout.column_bytes * pixels);
    gl::bind_storage({{scratch_spans_, kScratchSpans},
                      {scratch_counts_, kScratchCounts},
                      {scratch_exits_, kScratchExits},
                      {stats_, kStats},
                      {depth_bounds, kDepthBounds},
                      {rescan_list_, kRescan}});
  };

  set_uniforms(count_, layout, tile, cells, settings, image);
  bind_all();
  dispatch_strided(count_, pixels);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  prefix_sum.run(scratch_counts_, pixels);
  std::uint32_t total = 0;
  scratch_counts_.download(&total, 4, pixels * 4);
  image.set_span_count(span_base);
  image.reserve_spans(std::size_t(span_base) + total, max_binding_bytes);
  image.set_span_count(std::size_t(span_base) + total);

  set_uniforms(copy_, layout, tile, cells, settings, image);
  copy_.set("u_span_base", span_base);
  bind_all();
  dispatch_strided(copy_, pixels);
  std::uint32_t rescans = 0;
  rescan_list_.download(&rescans, 4);
  if (rescans != 0) {
    set_uniforms(rescan_, layout, tile, cells, settings, image);
    rescan_.set("u_span_base", span_base);
    rescan_.set("u_rescan_count", rescans);
    bind_all();
    dispatch_strided(rescan_, rescans);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  return total;
}

}  // namespace voxspan
