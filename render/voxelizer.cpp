#include "render/voxelizer.h"

#include "render/passes/depth_bounds.h"

#include <algorithm>
#include <cmath>

#include "voxspan/error.h"

namespace voxspan {
namespace {

// NVIDIA breaks on single bindings of 2 GiB or more (GPU-NOTES); 1 GiB keeps clear of it.
constexpr std::size_t kBindingCap = std::size_t(1) << 30;

// Both renderers' passes after the grid work in float and square view-space lengths (the GL
// splat's chords, the shading models' vectors), which overflows past about 1e19 world units:
// the GL renderer then lost every chord without a word, the CPU one shaded wrongly. A margin
// of 10.
constexpr double kFarthestDepth = 1e18;

}  // namespace

PerspectiveGrid fit_frame(const Camera& camera, std::span<const ParticleSphere> particles,
                          const VoxelizeOptions& options, gl::PassTimer& timer, FrameStats& stats) {
  PerspectiveGrid grid;
  CullCounts culled;
  {
    auto t = timer.cpu("frame");
    grid = PerspectiveGrid::fit(camera, particles, options.grid, &culled, options.combine_ranks);
  }
  const std::size_t input = particles.size();
  stats.set_count("particles.input", static_cast<std::int64_t>(input));
  stats.set_count("particles.visible", culled.visible);
  stats.set_count("particles.invalid", culled.invalid);
  stats.set_count("particles.culled_behind", culled.behind);
  stats.set_count("particles.culled_outside", culled.outside);
  stats.set_count("grid.layers", grid.layers());
  stats.set_count("grid.layers_needed", grid.layers_needed());
  stats.set_count("grid.layer_cap_hit", grid.layer_cap_hit() ? 1 : 0);
  stats.set_figure("grid.near", grid.near());
  stats.set_figure("grid.far", grid.far());
  stats.set_figure("grid.k_d", grid.k_d());
  stats.set_figure("grid.alpha_degrees", grid.alpha_degrees());
  if (grid.grid_far() > kFarthestDepth)
    throw make_error("the frame reaches ", grid.far(), " world units from the eye, beyond the ",
                     kFarthestDepth, " the renderers' float passes hold; scale the scene down");
  return grid;
}

void validate(const VoxelizeOptions& o) {
  validate(o.grid);
  if (!(o.gap_bridging >= 0) || !std::isfinite(o.gap_bridging))
    throw make_error("gap_bridging = ", o.gap_bridging, " is not a finite number >= 0");
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
                                   gl::PassTimer& timer, FrameStats& stats) {
  validate(options);
  const PerspectiveGrid grid = fit_frame(camera, particles, options, timer, stats);
  // Every count is reported every frame, zero or not, so each step's record has the same keys.
  for (const char* name : {"tiles", "bin.entries", "bin.large", "voxels", "spans.stored",
                           "spans.found", "pixels.capped"})
    stats.set_count(name, 0);
  {
    auto t = timer.gpu("clear");
    image_.reset(grid, clear_);
  }
  if (grid.empty()) return image_;
  const TileLayout layout = plan_tiles(grid.width(), grid.height(), grid.layers(),
                                       options.scratch_spans, options.tiles, max_binding_);
  stats.set_count("tiles", layout.count());
  if (particles.size_bytes() > max_binding_)
    throw make_error(particles.size(), " particles (", particles.size_bytes(),
                     " bytes) exceed one GL binding here (", max_binding_,
                     " bytes); pass fewer boundary particles per frame");
  const auto count = static_cast<std::uint32_t>(particles.size());
  {
    auto t = timer.gpu("upload");
    particles_.reserve(particles.size_bytes());
    particles_.upload(particles.data(), particles.size_bytes());
    cells_.upload(options.use_cell_states ? cells : CellStatesView{});
  }
  const Bins* bins = nullptr;
  {
    auto t = timer.gpu("bin");
    const std::vector<std::uint32_t> seed = options.combine_ranks && options.use_cell_states
                                                ? inner_full_depth_bounds(grid, cells)
                                                : std::vector<std::uint32_t>{};
    bins = &bin_.run(particles_, count, grid, layout, prefix_sum_,
                     options.binning == Binning::per_tile_lists, options.bin_tallies, seed);
    if (!bins->offsets.empty()) stats.set_count("bin.entries", bins->offsets.back());
    stats.set_count("bin.large", bins->large);
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
      auto t = timer.gpu("clear");
      clear_columns_.run(bits_, bin_.depth_bounds(), grid, layout, tile, cells_);
    }
    {
      auto t = timer.gpu("splat");
      SplatInput input{&particles_, count, nullptr, 0, 0, &bin_.large_list(), bins->large};
      if (!bins->offsets.empty()) {
        input.list = &bin_.lists();
        input.list_offset = bins->offsets[static_cast<std::size_t>(i)];
        input.list_count = bins->offsets[static_cast<std::size_t>(i) + 1] - input.list_offset;
      }
      splat_.run(bits_, input, grid, layout, tile, splat, prefix_sum_);
    }
    {
      auto t = timer.gpu("compress");
      spans += compress_.run(bits_, bin_.depth_bounds(), layout, tile, cells_, compress, image_,
                             spans, prefix_sum_, max_binding_);
    }
  }
  const CompressTallies tallies = compress_.tallies();
  stats.set_count("voxels", voxels);
  stats.set_count("spans.stored", spans);
  stats.set_count("spans.found", spans + tallies.spans_past_caps);
  stats.set_count("pixels.capped", tallies.capped_pixels);
  gl::check_error("voxelizing a frame");
  return image_;
}

}  // namespace voxspan
