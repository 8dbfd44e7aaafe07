// render/cpu/cpu_renderer.h - one full frame for one view on the CPU, for nodes without a GPU:
// the span image cast exactly (render/cpu/span_caster.h) instead of voxelized, then the passes
// on the span image (render/surface_passes.h) with the very rules of the GL passes, from the
// same model files (render/model/*.glsl compiled as C++ through render/model/host.h): connect,
// filter, normals, deep AO, shade. The two renderers differ by the span image alone, and cannot
// drift apart in the rest.
//
//   voxspan::CpuRenderer renderer;
//   voxspan::Recorder recorder(stats);
//   const voxspan::SpanImage& spans =
//       renderer.cast(camera, boundary_particles, cell_states, options.spans, recorder);
//   const voxspan::FloatImage& image =
//       renderer.shade(spans, options.surfaces, options.shade, recorder);
//
// Passes are host scopes of the caller's Recorder (no GL context is needed): "frame", "cast",
// then those of render/surface_passes.h, with the counts render/stat_names.h names. Threads:
// oneTBB; the pictures do not depend on their number. Memory follows the spans: no bit grid,
// no layers.
#pragma once

#include <span>
#include <vector>

#include "render/backdrop.h"
#include "render/cpu/span_caster.h"
#include "render/float_image.h"
#include "render/frame.h"
#include "render/model/host.h"
#include "render/recorder.h"
#include "render/shade_options.h"
#include "render/span_image.h"

namespace voxspan {

class CpuRenderer {
 public:
  // The span image of a frame: the grid fitted as the GL renderer fits it (fit_frame), the
  // spans exact. Valid until the next cast(); the caller may cut it in place (clip_at_walls).
  SpanImage& cast(const Camera& camera, std::span<const ParticleSphere> particles,
                  const CellStatesView& cells, const SpanOptions& options, Recorder& recorder);

  // The backdrop behind the fluid for the frames that follow (render/backdrop.h; null: the
  // environment), the image's size, kept by the caller while it is in use.
  void use_backdrop(const Backdrop* backdrop) { backdrop_ = backdrop; }

  // Connect, filter, normals, deep AO and shade a span image (this renderer's or one made
  // elsewhere: a composite of several ranks). Valid until the next shade().
  const FloatImage& shade(const SpanImage& spans, const SurfaceOptions& surfaces,
                          const ShadeOptions& shade, Recorder& recorder);
  // The same into `image` (resized when its size differs): a caller that keeps the picture
  // (the runtime's view products) saves copying it.
  void shade(const SpanImage& spans, const SurfaceOptions& surfaces, const ShadeOptions& shade,
             Recorder& recorder, FloatImage& image);

  // Per pixel the distance along the ray to the first span's entry (0: none), in the first
  // channel, as the GL FirstHitPass writes it. With `depths` (per span the (entry, exit)
  // view depths after the filter: surface_depths(), or GpuSurfaces::download_depths) the
  // filtered entry instead: the surface the picture shows.
  static void first_hit(const SpanImage& spans, FloatImage& out,
                        std::span<const glm::vec2> depths = {});
  // The per-span depths the last shade() drew its surfaces at; empty where no filter ran.
  std::span<const glm::vec2> surface_depths() const { return buffers_.depths; }

 private:
  class Passes;  // this renderer's SurfacePasses

  SpanCaster caster_;
  SpanImage spans_;
  FloatImage image_;
  model::HostBuffers buffers_;            // the surface data, kept from frame to frame
  std::vector<model::vec2> next_depths_;  // the filter's other buffer
  model::BackgroundCache background_;     // behind the pixels, while the camera stays
  const Backdrop* backdrop_ = nullptr;
  BackdropPyramid pyramid_;  // backdrop_'s, for refracted rays
};

}  // namespace voxspan
