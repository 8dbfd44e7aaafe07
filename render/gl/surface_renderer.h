// render/gl/surface_renderer.h - the GL renderer (render/gl/renderer.h) behind the surface-
// renderer interface (render/surface_renderer.h): the span image voxelized on the GPU, read back
// or replaced by an upload where asked, shaded there and read back.
#pragma once

#include <memory>

#include "render/gl/shader_library.h"
#include "render/gl/voxelizer.h"
#include "render/surface_renderer.h"

namespace voxspan {

// Needs a current GL context; compiles every pass. `voxelize`: how the GL passes work, its
// memory budget in particular (its SpanOptions part is each frame's).
std::unique_ptr<SurfaceRenderer> make_gl_surface_renderer(const gl::ShaderLibrary& shaders,
                                                          const VoxelizeOptions& voxelize);

}  // namespace voxspan
