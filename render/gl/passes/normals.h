// render/gl/passes/normals.h - surface normals ([ZD15] sec. 3.4, 4.5; the rule in
// render/model/surface_geometry.glsl): the Sobel operator along the links on the surface depths
// (filtered or not), outward world normals, octahedral in 32 bits each
// (render/gl/passes/normals.comp); then, where folds are on, the normals of crest points from
// their neighbours' off the crest, in place (render/gl/passes/crest_normals.comp). Reads: the span
// image, GpuSurfaces owners, links, depths, the backdrop's depths (where the fluid is cut at
// walls). Writes: GpuSurfaces normals. Cost: one thread per span in each dispatch, 9 linked depths
// per end, then 4 per end (4 stored normals at a crest); 8 bytes written per span (the paper's
// GTX 970: 8 ms at 1080p).
#pragma once

#include "render/gl/gpu_span_image.h"
#include "render/gl/gpu_surfaces.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"

namespace voxspan {

class NormalsPass {
 public:
  explicit NormalsPass(const gl::ShaderLibrary& shaders);
  // `backdrop`: render/backdrop.h's pixels, whose depths the normals read where `walls` says
  // (the fluid's spans cut at the walls: render/model/surface_geometry.glsl); `fold_step`
  // (SurfaceOptions) also marks the crests whose normals come from their neighbours.
  void run(const GpuSpanImage& image, const GpuSurfaces& surfaces, const gl::Buffer& backdrop,
           bool walls, double fold_step);

 private:
  gl::Program sobel_;
  gl::Program crests_;
};

}  // namespace voxspan
