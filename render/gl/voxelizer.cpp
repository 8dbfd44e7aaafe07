#include "render/gl/voxelizer.h"

#include "render/gl/passes/depth_bounds.h"
#include "render/stat_names.h"

#include <algorithm>
#include <cmath>

#include "voxspan/error.h"

namespace voxspan {
namespace {

// NVIDIA breaks on single bindings of 2 GiB or more (GPU-NOTES); 1 GiB keeps clear of it.
constexpr std::size_t kBindingCap = std::size_t(1) << 30;

}  // namespace

void validate(const VoxelizeOptions& o) {
  validate(static_cast<const SpanOptions&>(o));
  if (o.scratch_spans < 1 || o.scratch_spans > 64)
    throw make_error("scratch_spans = ", o.scratch_spans, " is outside 1..64");
  if (o.tiles.max_width < 0 || o.tiles.max_height < 0)
    throw make_error("tile max_width/max_height must be >= 0 (0 = no limit)");
}

Voxelizer::Voxelizer(const gl::ShaderLibrary& shaders)
    : clear_(shaders),
      clear_columns_(shaders),
      prefix_sum_(shaders),
      bin_(shaders),
      splat_(shaders),
      compress_(shaders) {
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  max_binding_ =
      std::min<std::size_t>(kBindingCap, static_cast<std::size_t>(std::max<GLint64>(block, 0)));
}

const GpuSpanImage& Voxelizer::run(const Camera& camera, std::span<const ParticleSphere> particles,
                                   const CellStatesView& cells, const VoxelizeOptions& options,
                                   Recorder& recorder) {
  validate(options);
  const PerspectiveGrid grid = fit_frame(camera, particles, options, recorder);
  // Every count is reported every frame, zero or not, so each step's record has the same keys.
  for (StatName name : {counter::tiles, counter::bin_entries, counter::bin_large, counter::voxels,
                        counter::spans_stored, counter::spans_found, counter::pixels_capped})
    recorder.count(name, 0);
  {
    auto t = recorder.device(pass::clear);
    const std::size_t pixel_bytes = image_.reset(grid);
    clear_.run(image_.pixels(), 0, pixel_bytes);
  }
  if (grid.empty()) return image_;
  const TileLayout layout = plan_tiles(grid.width(), grid.height(), grid.layers(),
                                       options.scratch_spans, options.tiles, max_binding_);
  recorder.count(counter::tiles, layout.count());
  if (particles.size_bytes() > max_binding_)
    throw make_error(particles.size(), " particles (", particles.size_bytes(),
                     " bytes) exceed one GL binding here (", max_binding_,
                     " bytes); pass fewer boundary particles per frame");
  const auto count = static_cast<std::uint32_t>(particles.size());
  {
    auto t = recorder.device(pass::upload);
    particles_.reserve(particles.size_bytes());
    particles_.upload(particles.data(), particles.size_bytes());
    cells_.upload(options.use_cell_states ? cells : CellStatesView{});
  }
  const Bins* bins = nullptr;
  {
    auto t = recorder.device(pass::bin);
    const std::vector<std::uint32_t> seed = options.combine_ranks && options.use_cell_states
                                                ? inner_full_depth_bounds(grid, cells)
                                                : std::vector<std::uint32_t>{};
    bins = &bin_.run(particles_, count, grid, layout, prefix_sum_,
                     options.binning == Binning::per_tile_lists, options.bin_tallies, seed);
    if (!bins->offsets.empty()) recorder.count(counter::bin_entries, bins->offsets.back());
    recorder.count(counter::bin_large, bins->large);
  }
  bits_.fit(layout.tile_bytes);
  compress_.begin_frame();
  const SplatSettings splat{options.gap_bridging, options.surface_splat, options.splat_threads};
  const CompressSettings compress{options.gap_bridging, options.max_spans, options.scratch_spans,
                                  options.span_edges};
  std::uint32_t spans = 0;
  std::int64_t voxels = 0;
  for (int i = 0; i < layout.count(); ++i) {
    const TileRect tile = layout.tile(i);
    voxels += std::int64_t(tile.pixels()) * grid.layers();
    {
      auto t = recorder.device(pass::clear);
      clear_columns_.run(bits_, bin_.depth_bounds(), grid, layout, tile, cells_);
    }
    {
      auto t = recorder.device(pass::splat);
      SplatInput input{&particles_, count, nullptr, 0, 0, &bin_.large_list(), bins->large};
      if (!bins->offsets.empty()) {
        input.list = &bin_.lists();
        input.list_offset = bins->offsets[static_cast<std::size_t>(i)];
        input.list_count = bins->offsets[static_cast<std::size_t>(i) + 1] - input.list_offset;
      }
      splat_.run(bits_, input, grid, layout, tile, splat, prefix_sum_);
    }
    {
      auto t = recorder.device(pass::compress);
      spans += compress_.run(bits_, bin_.depth_bounds(), layout, tile, cells_, compress, image_,
                             spans, prefix_sum_, max_binding_);
    }
  }
  const CompressTallies tallies = compress_.tallies();
  recorder.count(counter::voxels, voxels);
  recorder.count(counter::spans_stored, spans);
  recorder.count(counter::spans_found, spans + tallies.spans_past_caps);
  recorder.count(counter::pixels_capped, tallies.capped_pixels);
  gl::check_error("voxelizing a frame");
  return image_;
}

}  // namespace voxspan
