#include "render/frame.h"

#include <cmath>

#include "render/stat_names.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

// Both renderers' passes after the grid work in float and square view-space lengths (the GL
// splat's chords, the shading models' vectors), which overflows past about 1e19 frame units:
// the GL renderer then lost every chord without a word, the CPU one shaded wrongly. A margin
// of 10.
constexpr double kFarthestDepth = 1e18;
// Span images and first-hit distances leave the renderer as floats in world units (at most
// 3.4e38).
constexpr double kFarthestWorldDepth = 1e38;

}  // namespace

void validate(const SpanOptions& o) {
  validate(o.grid);
  if (!(o.gap_bridging >= 0) || !std::isfinite(o.gap_bridging))
    throw make_error("gap_bridging = ", o.gap_bridging, " is not a finite number >= 0");
}

PerspectiveGrid fit_frame(const Camera& camera, std::span<const ParticleSphere> particles,
                          const SpanOptions& options, Recorder& recorder) {
  PerspectiveGrid grid;
  CullCounts culled;
  {
    auto t = recorder.host(pass::frame);
    grid = PerspectiveGrid::fit(camera, particles, options.grid, &culled, options.combine_ranks);
  }
  recorder.count(counter::particles_input, static_cast<std::int64_t>(particles.size()));
  recorder.count(counter::particles_visible, culled.visible);
  recorder.count(counter::particles_invalid, culled.invalid);
  recorder.count(counter::particles_culled_behind, culled.behind);
  recorder.count(counter::particles_culled_outside, culled.outside);
  recorder.count(counter::grid_layers, grid.layers());
  recorder.count(counter::grid_layers_needed, grid.layers_needed());
  recorder.count(counter::grid_layer_cap_hit, grid.layer_cap_hit() ? 1 : 0);
  const double unit = options.unit;
  recorder.figure(figure::grid_near, grid.near() * unit);
  recorder.figure(figure::grid_far, grid.far() * unit);
  recorder.figure(figure::grid_k_d, grid.k_d());
  recorder.figure(figure::grid_alpha_degrees, grid.alpha_degrees());
  if (grid.grid_far() > kFarthestDepth)
    throw make_error("the frame reaches ", grid.far() * unit, " world units from the eye, past ",
                     kFarthestDepth, " times its unit of ", unit,
                     " world units (the camera's distance to its target as a power of two, or 1 "
                     "from 2^-32 to 2^32) that the renderers' float passes hold; leave out the "
                     "particles that far or aim the camera at them");
  if (grid.grid_far() * unit > kFarthestWorldDepth)
    throw make_error("the frame reaches ", grid.far() * unit,
                     " world units from the eye, past the ", kFarthestWorldDepth,
                     " that its float span and depth images hold; scale the scene down");
  return grid;
}

}  // namespace voxspan
