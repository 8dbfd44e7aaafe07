#include "render/cpu/surface_renderer.h"

#include "render/cpu/cpu_renderer.h"
#include "render/stat_names.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

class CpuSurfaceRenderer final : public SurfaceRenderer {
 public:
  void make_spans(const Camera& camera, std::span<const ParticleSphere> particles,
                  const CellStatesView& cells, const SpanOptions& options,
                  Recorder& recorder) override {
    spans_ = nullptr;
    spans_ = own_ = &renderer_.cast(camera, particles, cells, options, recorder);
  }

  // No copy and no upload: the images are in host memory.
  const SpanImage& host_spans(StatName, Recorder&) override { return spans(); }
  void use_spans(const SpanImage& spans, StatName, Recorder&) override {
    spans_ = &spans;
    own_ = nullptr;
  }

  void shade(const SurfaceOptions& surfaces, const ShadeOptions& shade, Recorder& recorder,
             FloatImage& picture) override {
    renderer_.shade(spans(), surfaces, shade, recorder, picture);
  }

  void use_backdrop(const Backdrop* backdrop, Recorder& recorder) override {
    renderer_.use_backdrop(backdrop);
    if (backdrop == nullptr) return;
    auto t = recorder.host(pass::scenery_cut);
    if (own_ == nullptr) {  // the caller's image: copied only when a wall cuts it
      if (!reaches_past_walls(spans(), *backdrop)) return;
      cut_ = spans();
      spans_ = own_ = &cut_;
    }
    clip_at_walls(*own_, *backdrop);
  }

  void first_hit(Recorder& recorder, FloatImage& out, HitSurface surface) override {
    auto t = recorder.host(pass::first_hit);
    CpuRenderer::first_hit(
        spans(), out,
        surface == HitSurface::shaded ? renderer_.surface_depths() : std::span<const glm::vec2>());
  }

 private:
  const SpanImage& spans() const {
    if (spans_ == nullptr) throw make_error("the CPU surface renderer has no span image yet");
    return *spans_;
  }

  CpuRenderer renderer_;
  const SpanImage* spans_ = nullptr;  // the frame's: the renderer's cast or the caller's, or cut_
  SpanImage* own_ = nullptr;          // spans_ when it may be cut in place
  SpanImage cut_;                     // the caller's image, copied to be cut at the walls
};

}  // namespace

std::unique_ptr<SurfaceRenderer> make_cpu_surface_renderer() {
  return std::make_unique<CpuSurfaceRenderer>();
}

}  // namespace voxspan
