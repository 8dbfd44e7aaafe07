// render/gl/passes/shade_pixels.h - the shading passes with one thread per pixel and no state
// between dispatches ([ZD15] sec. 3.5): opaque (render/gl/passes/shade_opaque.comp: the first
// entry, lit) and translucent (render/gl/passes/shade_translucent.comp: Fresnel at the first entry,
// Beer-Lambert over every span, exact past a span cap); the rules in
// render/model/shade_modes.glsl.
// Reads: the span image, GpuSurfaces depths, normals and (with deep AO) ao. Writes: the float
// image (linear RGBA per pixel).
// Cost: one thread per pixel; opaque reads one span, translucent every span of its pixel (the
// paper's GTX 970: 10 ms for translucency at 1080p).
#pragma once

#include <string_view>

#include "render/gl/gpu_float_image.h"
#include "render/gl/gpu_span_image.h"
#include "render/gl/gpu_surfaces.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"
#include "render/model/shade_uniforms.h"

namespace voxspan {

class ShadePixelsPass {
 public:
  // `shader`: render/gl/passes/shade_opaque.comp or shade_translucent.comp.
  ShadePixelsPass(const gl::ShaderLibrary& shaders, std::string_view shader);
  // `backdrop`: render/backdrop.h's pixels, read where uniforms.u_use_backdrop says.
  void run(const GpuSpanImage& image, const GpuSurfaces& surfaces,
           const model::ShadeUniforms& uniforms, const gl::Buffer& backdrop, GpuFloatImage& out);

 private:
  gl::Program program_;
};

}  // namespace voxspan
