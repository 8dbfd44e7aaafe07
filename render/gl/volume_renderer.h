// render/gl/volume_renderer.h - the GL volume renderer behind the volume-renderer interface
// (render/volume_renderer.h): the CPU caster's project, sort and bin, then the march on the GPU
// (render/gl/passes/volume_march.h), float sums, following adaptive sampling's plans made on the
// host (render/cpu/volume_adaptive.h) where the options ask. A rank's part of an MPI frame and
// the deep image go through the CPU caster (the GPU's part is not built).
#pragma once

#include <memory>

#include "render/gl/shader_library.h"
#include "render/volume_renderer.h"

namespace voxspan {

// Needs a current GL 4.5 context (render/gl/context.h).
std::unique_ptr<VolumeRenderer> make_gl_volume_renderer(const gl::ShaderLibrary& shaders);

}  // namespace voxspan
