// render/cpu/surface_renderer.h - the CPU renderer (render/cpu/cpu_renderer.h) behind the
// surface-renderer interface (render/surface_renderer.h): exact spans cast in host memory,
// shaded there; nothing to read back or upload.
#pragma once

#include <memory>

#include "render/surface_renderer.h"

namespace voxspan {

std::unique_ptr<SurfaceRenderer> make_cpu_surface_renderer();

}  // namespace voxspan
