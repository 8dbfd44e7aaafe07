// render/gl/passes/deep_ao.h - deep ambient occlusion ([ZD15] sec. 3.6;
// render/gl/passes/deep_ao.comp, the rule in render/model/deep_ao.glsl): per pixel, the occlusion
// of its front surface by the spans of every layer of neighbouring columns within a world
// radius.
// Reads: the span image, GpuSurfaces depths and normals. Writes: GpuSurfaces ao (one float per
// pixel; 1 where there is no fluid).
// Cost: one thread per pixel, `samples` columns each with a binary search and at most 4 spans.
#pragma once

#include "render/gl/gpu_span_image.h"
#include "render/gl/gpu_surfaces.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"
#include "render/model/shade_uniforms.h"

namespace voxspan {

class DeepAoPass {
 public:
  explicit DeepAoPass(const gl::ShaderLibrary& shaders);
  void run(const GpuSpanImage& image, const GpuSurfaces& surfaces,
           const model::ShadeUniforms& uniforms);

 private:
  gl::Program program_;
};

}  // namespace voxspan
