// render/backend.h - which renderer a process uses: the GL one (render/gl/renderer.h) or the CPU
// one (render/cpu/cpu_renderer.h), and why.
//   auto  the GL renderer on a GPU; where the GL context is a software one (Mesa's llvmpipe,
//         which emulates a GPU on the CPU) or none can be made, the CPU renderer, which casts
//         exact spans natively and is several times faster there (docs/benchmarks.md). A GL
//         platform named in the config (not `auto`) asks for the GL renderer, as `gl` does;
//   gl    the GL renderer on whatever GL context the platform gives (llvmpipe included), or
//         the context's error;
//   cpu   the CPU renderer; no GL context is made.
#pragma once

#include <memory>
#include <string>

#include "render/gl/context.h"
#include "render/surface_renderer.h"
#include "render/volume_renderer.h"

namespace voxspan {

namespace gl {
class ShaderLibrary;
}

struct BackendChoice {
  RenderBackend backend = RenderBackend::cpu;  // gl or cpu
  std::unique_ptr<gl::Context> context;        // the GL renderer's (current); null for cpu
  std::string why;                             // "auto: the GL context is llvmpipe (...)"
};

// Makes the GL context when the choice needs one. Throws voxspan::Error with the context's
// error when `gl` was asked for and none can be made.
BackendChoice choose_backend(RenderBackend wanted, const gl::ContextOptions& options);

// "GL renderer on EGL device 0 (...)" or "CPU renderer, 2 threads", and the reason.
std::string describe(const BackendChoice& choice);

// The recorder of the renderer chosen: the GL renderer's times its device scopes on the GPU.
std::unique_ptr<Recorder> make_recorder(const BackendChoice& choice);

// The surface renderer of `backend` (gl or cpu, as chosen). The GL one needs the context
// current and compiles its passes from `shaders`; `gpu_memory_budget` bounds its bit grid's
// tiles (bytes). The CPU one uses neither. Either renders frames far from unit scale in
// their own units (render/frame_units.h).
std::unique_ptr<SurfaceRenderer> make_surface_renderer(RenderBackend backend,
                                                       const gl::ShaderLibrary& shaders,
                                                       std::size_t gpu_memory_budget);

// The volume renderer of `backend` (`shaders`: the GL renderer's; a GL context must be current).
std::unique_ptr<VolumeRenderer> make_volume_renderer(RenderBackend backend,
                                                     const gl::ShaderLibrary& shaders);

}  // namespace voxspan
