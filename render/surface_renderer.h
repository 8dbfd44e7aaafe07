// render/surface_renderer.h - what a view asks of a renderer for a picture of the fluid's
// surfaces, whichever renderer the process uses (chosen once by renderer.backend:
// render/backend.h): the frame's span image from the boundary particles, that image in host
// memory or replaced by one made elsewhere (an MPI composite), the passes on it
// (render/surface_passes.h) into a picture in host memory, and the first-hit distances.
// Implementations: render/gl/surface_renderer.h (GL passes on a GPU) and
// render/cpu/surface_renderer.h (exact spans cast on the CPU). Both time and count into the
// caller's Recorder under the names of render/stat_names.h.
#pragma once

#include <span>

#include "render/backdrop.h"
#include "render/enum_names.h"
#include "render/float_image.h"
#include "render/frame.h"
#include "render/pending_picture.h"
#include "render/recorder.h"
#include "render/shade_options.h"
#include "render/span_image.h"
#include "render/srgb8_image.h"
#include "voxspan/cell_states.h"
#include "voxspan/error.h"

namespace voxspan {

// Which first surface SurfaceRenderer::first_hit measures.
enum class HitSurface { cast, shaded };

enum class RenderBackend { automatic, gl, cpu };
inline constexpr EnumName<RenderBackend> kRenderBackendNames[] = {
    {"auto", RenderBackend::automatic}, {"gl", RenderBackend::gl}, {"cpu", RenderBackend::cpu}};

// When shade_later() reads the picture later. On a GPU a read at once waits for every pass of the
// frame; on a software renderer (llvmpipe) the passes are done when the read starts and its
// buffers are host memory, so the copy for later costs more than the read (twice, at 1920x1080:
// docs/benchmarks.md). `always`: wherever EGL has fences (to run that path on llvmpipe).
enum class ReadLater { on_gpu, always, never };
inline constexpr EnumName<ReadLater> kReadLaterNames[] = {
    {"auto", ReadLater::on_gpu}, {"later", ReadLater::always}, {"wait", ReadLater::never}};

class SurfaceRenderer {
 public:
  virtual ~SurfaceRenderer() = default;

  // The frame's span image: voxelized (GL) or cast (CPU). Throws voxspan::Error on bad options,
  // a memory budget too small or a frame too deep (render/frame.h); bad particles (NaN,
  // radius <= 0) are counted and skipped.
  virtual void make_spans(const Camera& camera, std::span<const ParticleSphere> particles,
                          const CellStatesView& cells, const SpanOptions& options,
                          Recorder& recorder) = 0;
  // The frame's span image in host memory, valid until the next make_spans() or use_spans():
  // the GL renderer reads it back, timed as `pass`; the CPU renderer's is there.
  virtual const SpanImage& host_spans(StatName pass, Recorder& recorder) = 0;
  // The frame's span image from now on is `spans` (host memory, kept alive by the caller for the
  // frame): the GL renderer uploads it, timed as `pass`.
  virtual void use_spans(const SpanImage& spans, StatName pass, Recorder& recorder) = 0;
  // The passes on the frame's span image, the picture into `picture` (linear RGBA, row 0 at the
  // top; resized to the image): the GL renderer's read back as pass::readback.
  virtual void shade(const SurfaceOptions& surfaces, const ShadeOptions& shade, Recorder& recorder,
                     FloatImage& picture) = 0;
  // shade() with the picture read back later where `when` says and the renderer can: `picture`
  // is sized and its pixels arrive through the returned read (render/pending_picture.h; the
  // caller's until released); null where they are in `picture` already, as a renderer that
  // shades in host memory (the CPU one) leaves them by default.
  virtual PendingPicture* shade_later(const SurfaceOptions& surfaces, const ShadeOptions& shading,
                                      Recorder& recorder, FloatImage& picture, ReadLater /*when*/) {
    shade(surfaces, shading, recorder, picture);
    return nullptr;
  }
  // Whether shade_srgb8_later() with `when` converts on the renderer's device, for a picture only
  // 8-bit readers take. The GL renderer does on a GPU, and with ReadLater::always anywhere (to
  // run that path on llvmpipe); on a software renderer the conversion is the CPU's work on the
  // solver's thread and costs it more than the read it saves (docs/benchmarks.md), and the CPU
  // renderer's float picture is in host memory already.
  virtual bool packs_srgb8(ReadLater /*when*/) const { return false; }
  // shade_later() with the picture as 8-bit sRGB (linear_to_srgb8's bytes, render/srgb8_image.h)
  // in `picture`: a quarter of the bytes read back. Throws voxspan::Error where the renderer
  // cannot (packs_srgb8() false for every `when`).
  virtual PendingPicture* shade_srgb8_later(const SurfaceOptions& /*surfaces*/,
                                            const ShadeOptions& /*shading*/, Recorder& /*recorder*/,
                                            ImageRGBA8& /*picture*/, ReadLater /*when*/) {
    throw make_error("this renderer does not convert pictures to 8-bit sRGB");
  }
  // The backdrop shade() shows behind the fluid (render/backdrop.h; null: the environment), the
  // image's size, kept alive by the caller while in use; the frame's span image (made or
  // given before) is cut where its walls begin, timed as pass::scenery_cut.
  virtual void use_backdrop(const Backdrop* backdrop, Recorder& recorder) = 0;
  // Per pixel the distance along its ray to the frame's first span entry, 0 where there is
  // none, in the first channel, timed as pass::first_hit: of the spans as cast (what depth
  // images are made of), or of the surface the last shade drew (filtered: its positions give
  // the smooth normals a colouring of the surface needs, where the spheres' bumps would show).
  virtual void first_hit(Recorder& recorder, FloatImage& out, HitSurface surface) = 0;
};

}  // namespace voxspan
