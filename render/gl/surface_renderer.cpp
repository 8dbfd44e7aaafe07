#include "render/gl/surface_renderer.h"

#include "render/gl/gpu_float_image.h"
#include "render/gl/passes/cut_at_walls.h"
#include "render/gl/passes/first_hit.h"
#include "render/gl/passes/srgb8_pack.h"
#include "render/gl/picture_readback.h"
#include "render/gl/renderer.h"
#include "render/stat_names.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

class GlSurfaceRenderer final : public SurfaceRenderer {
 public:
  GlSurfaceRenderer(const gl::ShaderLibrary& shaders, const VoxelizeOptions& voxelize)
      : renderer_(shaders),
        first_hit_(shaders),
        cut_(shaders),
        pack_(shaders),
        voxelize_(voxelize) {}

  void make_spans(const Camera& camera, std::span<const ParticleSphere> particles,
                  const CellStatesView& cells, const SpanOptions& options,
                  Recorder& recorder) override {
    spans_ = nullptr;
    host_ = nullptr;
    static_cast<SpanOptions&>(voxelize_) = options;
    spans_ = &renderer_.voxelizer().run(camera, particles, cells, voxelize_, recorder);
  }

  const SpanImage& host_spans(StatName pass, Recorder& recorder) override {
    if (host_ == nullptr) {
      auto t = recorder.device(pass);
      spans().download(read_);
      host_ = &read_;
    }
    return *host_;
  }

  void use_spans(const SpanImage& spans, StatName pass, Recorder& recorder) override {
    auto t = recorder.device(pass);
    uploaded_.upload(spans);
    spans_ = &uploaded_;
    host_ = &spans;
  }

  void shade(const SurfaceOptions& surfaces, const ShadeOptions& shade, Recorder& recorder,
             FloatImage& picture) override {
    const GpuFloatImage& image = renderer_.shade(spans(), surfaces, shade, recorder);
    auto t = recorder.device(pass::readback);
    image.download(picture);
  }

  PendingPicture* shade_later(const SurfaceOptions& surfaces, const ShadeOptions& shading,
                              Recorder& recorder, FloatImage& picture, ReadLater when) override {
    if (!reads_later(when)) {
      shade(surfaces, shading, recorder, picture);
      return nullptr;
    }
    const GpuFloatImage& image = renderer_.shade(spans(), surfaces, shading, recorder);
    // A host scope: what the solver's thread spends issuing it (a device scope would wait).
    auto t = recorder.host(pass::readback);
    PendingPicture& read = readback_.issue(image);
    picture.width = image.width();
    picture.height = image.height();
    picture.rgba.resize(std::size_t(image.width()) * std::size_t(image.height()) * 4);
    return &read;
  }

  bool packs_srgb8(ReadLater when) const override { return when == ReadLater::always || on_gpu(); }

  PendingPicture* shade_srgb8_later(const SurfaceOptions& surfaces, const ShadeOptions& shading,
                                    Recorder& recorder, ImageRGBA8& picture,
                                    ReadLater when) override {
    const GpuFloatImage& image = renderer_.shade(spans(), surfaces, shading, recorder);
    {
      auto t = recorder.device(pass::srgb8_pack);
      pack_.run(image, packed_);
    }
    picture.width = image.width();
    picture.height = image.height();
    picture.pixels.resize(std::size_t(image.width()) * std::size_t(image.height()) * 4);
    if (!reads_later(when)) {
      auto t = recorder.device(pass::readback);
      if (!picture.pixels.empty()) packed_.download(picture.pixels.data(), picture.pixels.size());
      return nullptr;
    }
    auto t = recorder.host(pass::readback);  // as in shade_later
    return &readback_.issue_srgb8(packed_, image.width(), image.height());
  }

  void use_backdrop(const Backdrop* backdrop, Recorder& recorder) override {
    renderer_.use_backdrop(backdrop);
    if (backdrop == nullptr) return;
    auto t = recorder.device(pass::scenery_cut);
    cut_.run(spans(), renderer_.backdrop_buffer());
    host_ = nullptr;  // a copy in host memory is uncut
  }

  void first_hit(Recorder& recorder, FloatImage& out, HitSurface surface) override {
    auto t = recorder.device(pass::first_hit);
    first_hit_.run(
        spans(),
        surface == HitSurface::shaded ? renderer_.surfaces().depths(spans()) : spans().spans(),
        depth_);
    depth_.download(out);
  }

 private:
  // A GPU is told apart from a software renderer as the staging does it (render/gl/objects.h).
  static bool on_gpu() {
    const gl::ReadbackStaging* staging = gl::current_staging();
    return staging != nullptr && staging->in_use();
  }

  bool reads_later(ReadLater when) const {
    if (when == ReadLater::never || !readback_.available()) return false;
    return when == ReadLater::always || on_gpu();
  }

  const GpuSpanImage& spans() const {
    if (spans_ == nullptr) throw make_error("the GL surface renderer has no span image yet");
    return *spans_;
  }

  Renderer renderer_;
  FirstHitPass first_hit_;
  CutAtWallsPass cut_;
  Srgb8PackPass pack_;
  gl::Buffer packed_;  // the picture as 8-bit sRGB (shade_srgb8_later)
  VoxelizeOptions voxelize_;
  const GpuSpanImage* spans_ = nullptr;  // the frame's: the voxelizer's or uploaded_
  GpuSpanImage uploaded_;
  const SpanImage* host_ =
      nullptr;  // the frame's in host memory where known: read_ or the caller's
  SpanImage read_;
  GpuFloatImage depth_;
  gl::PictureReadback readback_;
};

}  // namespace

std::unique_ptr<SurfaceRenderer> make_gl_surface_renderer(const gl::ShaderLibrary& shaders,
                                                          const VoxelizeOptions& voxelize) {
  return std::make_unique<GlSurfaceRenderer>(shaders, voxelize);
}

}  // namespace voxspan
