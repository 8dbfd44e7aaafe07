// render/frame.h - the start of a frame on either renderer: what its span image follows
// (SpanOptions: the grid, gap bridging, the span cap, the cell states, the other ranks) and
// the perspective grid fitted to the particles the camera sees (fit_frame, [ZD15] sec. 4.2),
// with what the fit counted. The GL renderer's VoxelizeOptions (render/gl/voxelizer.h) adds
// how its passes work; the CPU renderer's spans need nothing more.
#pragma once

#include <cstdint>
#include <span>

#include "render/camera.h"
#include "render/perspective_grid.h"
#include "render/recorder.h"

namespace voxspan {

struct SpanOptions {
  GridOptions grid;
  double gap_bridging = 0;      // g: gaps shorter than this along the ray close (world units)
  std::uint32_t max_spans = 0;  // cap on stored spans per pixel (sec. 3.1); 0 = no cap
  bool use_cell_states = true;  // skip inner-empty, fill inner-full cells (sec. 4.3)
  // The other processes rendering into the same grid (PerspectiveGrid::fit); empty: none.
  // With them, this process's inner-full cells need not lie between its own boundary
  // particles (another rank may hold the fluid's far side).
  DepthRangeCombine combine_ranks;
  // World units per unit of the frame's lengths (render/frame_units.h), so that fit_frame
  // records and refuses in world units; 1 unless the frame was rescaled.
  double unit = 1;
};

// Throws voxspan::Error naming the option that is out of range.
void validate(const SpanOptions& options);

// A frame's perspective grid, fitted to the particles the camera sees (options.grid,
// options.combine_ranks), timed as pass::frame, with its counts and figures (particles.*,
// grid.*: render/stat_names.h, in world units). Throws voxspan::Error (its counts recorded)
// when the visible particles reach past 1e18 frame units from the eye (the passes after it
// work in float, whose squares of lengths overflow there; render/frame_units.h rescales frames
// far from unit scale) or past 1e38 world units (the float span and depth images that leave
// the renderer hold no more).
PerspectiveGrid fit_frame(const Camera& camera, std::span<const ParticleSphere> particles,
                          const SpanOptions& options, Recorder& recorder);

}  // namespace voxspan
