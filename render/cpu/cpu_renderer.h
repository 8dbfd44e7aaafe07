// render/cpu/cpu_renderer.h - one full frame for one view on the CPU, for nodes without a GPU:
// the span image cast exactly (render/cpu/span_caster.h) instead of voxelized, then the very
// rules of the GPU passes, from the same model files (render/model/*.glsl compiled as C++
// through render/model/cpu_host.h): connect, filter, normals, deep AO, shade. The two
// renderers differ by the voxelization alone, and cannot drift apart in the rest.
//
//   voxspan::CpuRenderer renderer;
//   const voxspan::SpanImage& spans =
//       renderer.cast(camera, boundary_particles, cell_states, options.voxelize, timer, stats);
//   const voxspan::FloatImage& image =
//       renderer.shade(spans, options.surfaces, options.shade, timer, stats);
//
// Passes are timed as CPU scopes of the caller's gl::PassTimer (no GL context is needed):
// "frame", "cast", then "connect", "filter", "normals", "deep_ao", "shade" as the GPU renderer
// names them, with the same counts in FrameStats. Threads: oneTBB; the pictures do not
// depend on their number. Memory follows the spans: no bit grid, no layers.
#pragma once

#include <span>
#include <vector>

#include "render/cpu/span_caster.h"
#include "render/model/cpu_host.h"
#include "render/float_image.h"
#include "render/frame_stats.h"
#include "render/gl/pass_timer.h"
#include "render/shade_options.h"
#include "render/span_image.h"
#include "render/voxelizer.h"

namespace voxspan {

class CpuRenderer {
 public:
  // The span image of a frame: the grid fitted as the GPU's voxelizer fits it (options.grid,
  // options.combine_ranks), the spans exact. Valid until the next cast().
  const SpanImage& cast(const Camera& camera, std::span<const ParticleSphere> particles,
                        const CellStatesView& cells, const VoxelizeOptions& options,
                        gl::PassTimer& timer, FrameStats& stats);

  // Connect, filter, normals, deep AO and shade a span image (this renderer's or one made
  // elsewhere: a composite of several ranks). Valid until the next shade().
  const FloatImage& shade(const SpanImage& spans, const SurfaceOptions& surfaces,
                          const ShadeOptions& shade, gl::PassTimer& timer, FrameStats& stats);
  // The same into `image` (resized when its size differs): a caller that keeps the picture
  // (the runtime's view products) saves copying it.
  void shade(const SpanImage& spans, const SurfaceOptions& surfaces, const ShadeOptions& shade,
             gl::PassTimer& timer, FrameStats& stats, FloatImage& image);

  // Per pixel the distance along the ray to the first span's entry (0: none), in the first
  // channel, as the GPU's FirstHitPass writes it. With `depths` (per span the (entry, exit)
  // view depths after the filter: surface_depths(), or GpuSurfaces::download_depths) the
  // filtered entry instead: the surface the picture shows.
  static void first_hit(const SpanImage& spans, FloatImage& out,
                        std::span<const glm::vec2> depths = {});
  // The per-span depths the last shade() drew its surfaces at; empty where no filter ran.
  std::span<const glm::vec2> surface_depths() const { return buffers_.depths; }

 private:
  SpanCaster caster_;
  SpanImage spans_;
  FloatImage image_;
  model::HostBuffers buffers_;            // the surface data, kept from frame to frame
  std::vector<model::vec2> next_depths_;  // the filter's other buffer
  model::BackgroundCache background_;     // behind the pixels, while the camera stays
};

}  // namespace voxspan
