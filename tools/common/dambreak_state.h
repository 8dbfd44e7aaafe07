// tools/common/dambreak_state.h - a dam-break state for the shading tools: the fluid particles of
// the WCSPH solver (examples/dambreak) run to a time, or of the Ritter-profile test scene
// (tools/scenes/scenes.h) when the examples are not built, classified into boundary particles
// and cell states by the adapter's classifier (voxspan/classify.h), with a camera, the ground
// and the fluid's scale. Solver states are cached in a file, since reaching a splash takes
// minutes on two cores.
#pragma once

#include <string>
#include <vector>

#include "render/camera.h"
#include "render/shade_options.h"
#include "voxspan/classify.h"

namespace voxspan::tools {

struct DamBreakState {
  std::string description;
  std::vector<float> x, y, z;  // fluid particle centres
  double spacing = 0;          // particle spacing at rest
  glm::dvec3 up{0, 0, 1};      // the solver's z is up
  double ground = 0;           // tank floor
  double length = 1;           // the column's width: the scene's scale
  Camera camera;               // an oblique view of the tank (size set by the caller)
  Classification classification;
};

// The solver (when built) run to Martin & Moyce's T = t sqrt(2 g / a) with about `particles`
// fluid particles, loaded from `cache` when it holds that state, saved there otherwise.
// Throws voxspan::Error when the examples are not built or the cache cannot be written.
DamBreakState solver_dam_break(double particles, double nondimensional_time,
                               const std::string& cache);
// The Ritter-profile test scene at t seconds.
DamBreakState ritter_dam_break(double particles, double t);

bool have_solver();

// The benchmarks' shading of a state, in its own scale: the ground at its floor with a checker
// a third of the column wide, a blue-green tint through the column, deep AO (when on) over four
// spacings.
ShadeOptions bench_shading(const DamBreakState& s);

// The shading tools' scene: the Ritter profile at `time` seconds (< 0: 0.3) when `ritter`, else
// the solver at T = `time` (< 0: 5, the run-up on the far wall), cached in `cache`.
DamBreakState dam_break_state(bool ritter, double particles, double time, const std::string& cache);

}  // namespace voxspan::tools
