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
#include "tools/common/tool_args.h"
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

// The flags of the tools that load a state: --state FILE (the solver's cache) and --ritter (the
// test scene instead of the solver).
struct StateFlags {
  std::string state = "build/dambreak_state.bin";
  bool ritter = !have_solver();
};
inline bool read_state_flag(Arg& arg, StateFlags& f) {
  return arg.value("--state", f.state) || arg.flag("--ritter", f.ritter);
}

// The shading tools' scene, about `scene.particles` of them: the Ritter profile at `scene.time`
// seconds (< 0: 0.3) with --ritter, else the solver at T = `scene.time` (< 0: 5, the run-up on
// the far wall), cached in --state's file.
DamBreakState dam_break_state(const StateFlags& flags, const SceneArgs& scene);

}  // namespace voxspan::tools
