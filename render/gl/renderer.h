// render/gl/renderer.h - one full frame of [ZD15] for one view on the GPU: voxelize (sec.
// 3.1-3.2, 4.1-4.4) -> the passes on the span image (render/surface_passes.h: connect,
// filter, normals, deep AO, shade) -> a float image (linear RGBA, row 0 at the top), left on
// the GPU for the caller to read back or encode.
//
//   voxspan::Renderer renderer(shaders);               // compiles every pass once
//   voxspan::RenderOptions options;                     // voxelize, surfaces, shade
//   voxspan::gl::GpuRecorder recorder(stats, context.has_gpu_timers());
//   const voxspan::GpuFloatImage& image =
//       renderer.render(camera, boundary_particles, cell_states, options, recorder);
//   voxspan::FloatImage pixels = image.download();      // for insitu/outputs/formats/png_image.h
//
// Every pass is a device scope of the caller's Recorder, named and counted as
// render/stat_names.h says. shade() runs the passes after the voxelization on a span image made
// elsewhere (e.g. one composited from several ranks).
#pragma once

#include <span>

#include "render/gl/gpu_float_image.h"
#include "render/gl/gpu_span_image.h"
#include "render/gl/gpu_surfaces.h"
#include "render/gl/passes/connect.h"
#include "render/gl/passes/deep_ao.h"
#include "render/gl/passes/filter.h"
#include "render/gl/passes/normals.h"
#include "render/gl/passes/shade_pixels.h"
#include "render/gl/passes/shade_refractive.h"
#include "render/gl/shader_library.h"
#include "render/gl/voxelizer.h"
#include "render/recorder.h"
#include "render/backdrop.h"
#include "render/shade_options.h"

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
                              Recorder& recorder);

  // The backdrop behind the fluid for the frames that follow (render/backdrop.h; null: the
  // environment), the image's size, kept alive by the caller while in use; copied to the GPU
  // when its version is new, its pyramid too before a refractive frame.
  void use_backdrop(const Backdrop* backdrop);
  // The last backdrop's pixels on the GPU (one unused pixel before any).
  const gl::Buffer& backdrop_buffer() const { return backdrop_; }

  // Connect, filter, normals, deep AO and shade a span image.
  const GpuFloatImage& shade(const GpuSpanImage& spans, const SurfaceOptions& surfaces,
                             const ShadeOptions& shade, Recorder& recorder);

  const GpuFloatImage& image() const { return image_; }
  const GpuSurfaces& surfaces() const { return surfaces_; }
  Voxelizer& voxelizer() { return voxelizer_; }

 private:
  class Passes;           // this renderer's SurfacePasses
  void upload_pyramid();  // of backdrop_given_, after its pixels, where it is new

  Voxelizer voxelizer_;
  ConnectPass connect_;
  FilterPass filter_;
  NormalsPass normals_;
  DeepAoPass deep_ao_;
  ShadePixelsPass opaque_, translucent_;
  ShadeRefractivePass refractive_;
  GpuSurfaces surfaces_;
  GpuFloatImage image_;
  gl::Buffer backdrop_;
  std::uint64_t backdrop_version_ = 0;
  const Backdrop* backdrop_given_ = nullptr;  // use_backdrop's, kept alive by the caller
  BackdropPyramid pyramid_;                   // its, after its pixels in backdrop_ (refraction)
};

}  // namespace voxspan
