#include "render/gl/passes/normals.h"

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {

NormalsPass::NormalsPass(const gl::ShaderLibrary& shaders)
    : sobel_(shaders.compute("render/gl/passes/normals.comp", binding::surface_defines())),
      crests_(shaders.compute("render/gl/passes/crest_normals.comp", binding::surface_defines())) {}

void NormalsPass::run(const GpuSpanImage& image, const GpuSurfaces& surfaces,
                      const gl::Buffer& backdrop, bool walls, double fold_step) {
  if (image.span_count() == 0) return;
  surfaces.bind(image);
  backdrop.bind(GL_SHADER_STORAGE_BUFFER, binding::kWallDepths);
  sobel_.set("u_walls_cut", walls ? 1 : 0);
  set_grid_uniforms(sobel_, image.grid());
  dispatch_threads(sobel_, image.span_count());
  if (fold_step > 0.0) {  // crests lie only where folds can (on_crest)
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    crests_.set("u_fold_step", float(fold_step));
    set_grid_uniforms(crests_, image.grid());
    dispatch_threads(crests_, image.span_count());
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace voxspan
