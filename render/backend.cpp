#include "render/backend.h"

#include <tbb/info.h>

#include "render/cpu/surface_renderer.h"
#include "render/cpu/volume_renderer.h"
#include "render/frame_units.h"
#include "render/gl/gpu_recorder.h"
#include "render/gl/info.h"
#include "render/gl/surface_renderer.h"
#include "render/gl/volume_renderer.h"
#include "voxspan/error.h"

namespace voxspan {

BackendChoice choose_backend(RenderBackend wanted, const gl::ContextOptions& options) {
  BackendChoice c;
  if (wanted == RenderBackend::cpu) {
    c.why = "renderer.backend: cpu";
    return c;
  }
  // A GL platform named (in the config, or in VOXSPAN_GL_PLATFORM, which overrides it) asks
  // for the GL renderer: its failure is an error.
  if (wanted == RenderBackend::gl ||
      gl::requested_platform(options.platform) != gl::Platform::automatic) {
    c.context = std::make_unique<gl::Context>(options);
    c.backend = RenderBackend::gl;
    c.why = wanted == RenderBackend::gl ? "renderer.backend: gl"
                                        : std::string("auto: a GL platform is named (") +
                                              gl::platform_name(c.context->platform()) + ")";
    return c;
  }
  if (gl::only_software_devices()) {
    c.why =
        "auto: EGL's only device is Mesa's software one (llvmpipe, a GPU emulated on the "
        "CPU); renderer.backend: gl uses it";
    return c;
  }
  try {
    c.context = std::make_unique<gl::Context>(options);
  } catch (const Error& e) {
    c.why = std::string("auto: no GL context (") + e.what() + ")";
    return c;
  }
  const gl::Info info = gl::query_info(*c.context);
  if (gl::software_renderer()) {
    c.context.reset();
    c.why = "auto: the GL context is " + info.renderer +
            ", a GPU emulated on the CPU; renderer.backend: gl uses it";
    return c;
  }
  c.backend = RenderBackend::gl;
  c.why = "auto: a GPU (" + info.renderer + ")";
  return c;
}

std::string describe(const BackendChoice& choice) {
  if (choice.backend == RenderBackend::gl)
    return "GL renderer on " + choice.context->description() + " (" + choice.why + ")";
  return "CPU renderer, " + std::to_string(tbb::info::default_concurrency()) + " threads (" +
         choice.why + ")";
}

std::unique_ptr<Recorder> make_recorder(const BackendChoice& choice) {
  if (!choice.context) return std::make_unique<Recorder>();
  return std::make_unique<gl::GpuRecorder>(choice.context->has_gpu_timers());
}

std::unique_ptr<SurfaceRenderer> make_surface_renderer(RenderBackend backend,
                                                       const gl::ShaderLibrary& shaders,
                                                       std::size_t gpu_memory_budget) {
  if (backend == RenderBackend::cpu) return in_frame_units(make_cpu_surface_renderer());
  VoxelizeOptions voxelize;
  voxelize.tiles.memory_budget = gpu_memory_budget;
  return in_frame_units(make_gl_surface_renderer(shaders, voxelize));
}

std::unique_ptr<VolumeRenderer> make_volume_renderer(RenderBackend backend,
                                                     const gl::ShaderLibrary& shaders) {
  if (backend == RenderBackend::gl) return make_gl_volume_renderer(shaders);
  return make_cpu_volume_renderer();
}

}  // namespace voxspan
