// render/stat_names.h - the names a frame of either renderer reports under, each written once:
// the renderers report with these, and the stats records (stats.jsonl: docs/runtime.md), the
// benchmarks and the tests read by them. The views add their own beside their code.
#pragma once

#include "render/recorder.h"

namespace voxspan {

// Passes, in the order a frame runs them.
namespace pass {
inline constexpr StatName frame{"frame"};  // the perspective grid fitted (both)
// The GL voxelization ([ZD15] sec. 3.1-4.4; clear runs once, then once per tile with splat
// and compress).
inline constexpr StatName clear{"clear"};
inline constexpr StatName upload{"upload"};
inline constexpr StatName bin{"bin"};
inline constexpr StatName splat{"splat"};
inline constexpr StatName compress{"compress"};
inline constexpr StatName cast{"cast"};  // the CPU renderer's exact spans
// The passes on the span image (render/surface_passes.h), both renderers.
inline constexpr StatName connect{"connect"};
inline constexpr StatName filter{"filter"};
inline constexpr StatName normals{"normals"};
inline constexpr StatName deep_ao{"deep_ao"};
inline constexpr StatName shade{"shade"};
// The fluid's spans cut where a backdrop's walls begin (render/backdrop.h; both).
inline constexpr StatName scenery_cut{"scenery_cut"};
// The picture as 8-bit sRGB on the GPU, for pictures only 8-bit readers take (GL).
inline constexpr StatName srgb8_pack{"srgb8_pack"};
// Into host memory (the GL renderer's read-backs; the CPU renderer's images are there).
inline constexpr StatName readback{"readback"};            // the picture
inline constexpr StatName first_hit{"first_hit"};          // the first-hit distances
inline constexpr StatName span_readback{"span_readback"};  // the span image, for an output
// A volume view's frame (render/volume_renderer.h).
inline constexpr StatName volume{"volume"};
}  // namespace pass

// Counts.
namespace counter {
// The particles the frame was given and what the grid's fit made of them.
inline constexpr StatName particles_input{"particles.input"};
inline constexpr StatName particles_visible{"particles.visible"};
inline constexpr StatName particles_invalid{"particles.invalid"};  // NaN or radius <= 0
inline constexpr StatName particles_culled_behind{"particles.culled_behind"};
inline constexpr StatName particles_culled_outside{"particles.culled_outside"};
inline constexpr StatName grid_layers{"grid.layers"};
inline constexpr StatName grid_layers_needed{"grid.layers_needed"};
inline constexpr StatName grid_layer_cap_hit{"grid.layer_cap_hit"};
// The span image.
inline constexpr StatName tiles{"tiles"};
inline constexpr StatName bin_entries{"bin.entries"};  // GL: particle-tile pairs binned
inline constexpr StatName bin_large{"bin.large"};      // GL: particles splatted on their own
inline constexpr StatName voxels{"voxels"};            // GL: voxels of every tile
inline constexpr StatName cast_cell_boxes{"cast.cell_boxes"};    // CPU: inner-full cells cast
inline constexpr StatName cast_chord_tests{"cast.chord_tests"};  // CPU: ray-sphere tests
inline constexpr StatName spans_stored{"spans.stored"};
inline constexpr StatName spans_found{"spans.found"};  // before the cap
inline constexpr StatName pixels_capped{"pixels.capped"};
// The passes on the span image.
inline constexpr StatName links_unlinkable_spans{"links.unlinkable_spans"};
inline constexpr StatName filter_iterations{"filter.iterations"};
inline constexpr StatName refract_dispatches{"refract.dispatches"};
inline constexpr StatName refract_unfinished{"refract.unfinished"};
inline constexpr StatName refract_events{"refract.events"};            // GL
inline constexpr StatName refract_most_events{"refract.most_events"};  // GL
// A volume frame: kVolumeCountNames (render/volume.h).
}  // namespace counter

// Figures: the frame's perspective grid.
namespace figure {
inline constexpr StatName grid_near{"grid.near"};
inline constexpr StatName grid_far{"grid.far"};
inline constexpr StatName grid_k_d{"grid.k_d"};
inline constexpr StatName grid_alpha_degrees{"grid.alpha_degrees"};
// A volume frame's VolumeCounts::error_bound.
inline constexpr StatName volume_error_bound{"volume.error_bound"};
}  // namespace figure

}  // namespace voxspan
