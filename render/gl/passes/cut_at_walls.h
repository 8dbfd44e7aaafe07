// render/gl/passes/cut_at_walls.h - the fluid's span image cut where the walls of a backdrop
// begin (render/backdrop.h: clip_at_walls is the same rule on the host), in place, so that a
// frame with scenery reads nothing back. Reads: the backdrop (vec4 per pixel, its w the walls'
// depth). Writes: the span image's records and the exits of the spans it cuts.
// Cost: one thread per pixel; a pixel the walls do not cut reads its record and one span.
#pragma once

#include "render/gl/gpu_span_image.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"

namespace voxspan {

class CutAtWallsPass {
 public:
  explicit CutAtWallsPass(const gl::ShaderLibrary& shaders);
  void run(const GpuSpanImage& image, const gl::Buffer& backdrop);

 private:
  gl::Program program_;
};

}  // namespace voxspan
