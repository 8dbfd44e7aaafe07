// render/gl/passes/shade_refractive.h - refractive shading ([ZD15] sec. 3.5, Listing 2;
// render/gl/passes/shade_refractive.comp, the rule in render/model/column_march.glsl): each
// pixel's ray marches through the columns, refracting at every surface it meets (several
// bounces, total internal reflection), absorbed along the way, and leaves to the environment.
// Reads: the span image, GpuSurfaces depths, normals and (with deep AO) ao. Writes: the float
// image; keeps a 96-byte ray record per pixel between dispatches.
// Cost: one thread per pixel per dispatch, at most ShadeOptions::march_budget column events
// each (bounded work per invocation); dispatches repeat, with a 4-byte read-back each, until no
// ray is active (the paper's GTX 970: 359 ms for two paths per pixel at 1080p).
#pragma once

#include <cstdint>

#include "render/gl/gpu_float_image.h"
#include "render/gl/gpu_span_image.h"
#include "render/gl/gpu_surfaces.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"
#include "render/model/shade_uniforms.h"
#include "render/shade_options.h"
#include "render/surface_passes.h"

namespace voxspan {

class ShadeRefractivePass {
 public:
  explicit ShadeRefractivePass(const gl::ShaderLibrary& shaders);
  // `options`: the bounces and march_budget (column events per ray per dispatch); at most
  // refract_dispatch_limit() march dispatches (render/shade_options.h). `backdrop`:
  // render/backdrop.h's pixels, read where uniforms.u_use_backdrop says.
  RefractTally run(const GpuSpanImage& image, const GpuSurfaces& surfaces,
                   const model::ShadeUniforms& uniforms, const ShadeOptions& options,
                   const gl::Buffer& backdrop, GpuFloatImage& out);

 private:
  gl::Program begin_, march_, resolve_;
  gl::Buffer rays_, active_, blocks_;
};

}  // namespace voxspan
