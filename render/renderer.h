// render/renderer.h - one full frame of [ZD15] for one view: voxelize (sec. 3.1-3.2, 4.1-4.4)
// -> connect (3.3) -> filter (3.4, 4.6) -> normals (3.4, 4.5) -> deep AO (3.6, optional) ->
// shade (3.5: opaque, translucent or refractive) -> a float image (linear RGBA, row 0 at the
// top), left on the GPU for the caller to read back or encode.
//
//   voxspan::Renderer renderer(shaders);               // compiles every pass once
//   voxspan::RenderOptions options;                     // voxelize, surfaces, shade
//   const voxspan::GpuFloatImage& image =
//       renderer.render(camera, boundary_particles, cell_states, options, timer, stats);
//   voxspan::FloatImage pixels = image.download();      // for insitu/outputs/png_image.h
//
// Every pass is timed through the caller's gl::PassTimer (names: the voxelizer's, then
// "connect", "filter", "normals", "deep_ao", "shade") and reports into FrameStats (counts
// "links.unlinkable_spans", "filter.iterations", "refract.dispatches", "refract.unfinished",
// "refract.events", "refract.most_events").
// shade() runs the passes after the voxelization on a span image made elsewhere (e.g. one
// composited from several ranks).
#pragma once

#include <span>

#include "render/float_image.h"
#include "render/frame_stats.h"
#include "render/gl/pass_timer.h"
#include "render/gl/shader_library.h"
#include "render/gpu_span_image.h"
#include "render/gpu_surfaces.h"
#include "render/passes/connect.h"
#include "render/passes/deep_ao.h"
#include "render/passes/filter.h"
#include "render/passes/normals.h"
#include "render/passes/shade_pixels.h"
#include "render/passes/shade_refractive.h"
#include "render/shade_options.h"
#include "render/voxelizer.h"

namespace voxspan {

struct RenderOptions {
  VoxelizeOptions voxelize;
  SurfaceOptions surfaces;
  ShadeOptions shade;
};

class Renderer {
 public:
  // Needs a current GL context; compiles every pass.
  explicit Renderer(const gl::ShaderLibrary& shaders);

  // One frame. The image stays valid until the next call. Throws voxspan::Error on bad options
  // (naming them) or a memory budget too small for one tile row.
  const GpuFloatImage& render(const Camera& camera, std::span<const ParticleSphere> particles,
                              const CellStatesView& cells, const RenderOptions& options,
                              gl::PassTimer& timer, FrameStats& stats);

  // Connect, filter, normals, deep AO and shade a span image.
  const GpuFloatImage& shade(const GpuSpanImage& spans, const SurfaceOptions& surfaces,
                             const ShadeOptions& shade, gl::PassTimer& timer, FrameStats& stats);

  const GpuFloatImage& image() const { return image_; }
  const GpuSurfaces& surfaces() const { return surfaces_; }
  Voxelizer& voxelizer() { return voxelizer_; }

 private:
  Voxelizer voxelizer_;
  ConnectPass connect_;
  FilterPass filter_;
  NormalsPass normals_;
  DeepAoPass deep_ao_;
  ShadePixelsPass opaque_, translucent_;
  ShadeRefractivePass refractive_;
  GpuSurfaces surfaces_;
  GpuFloatImage image_;
};

}  // namespace voxspan
