#include "render/gl/renderer.h"

#include "render/surface_passes.h"

namespace voxspan {

// The steps of render/surface_passes.h as GL passes on one span image.
class Renderer::Passes final : public SurfacePasses {
 public:
  Passes(Renderer& r, const GpuSpanImage& spans, const model::ShadeUniforms& uniforms)
      : r_(r), spans_(spans), uniforms_(uniforms) {}

 private:
  Recorder::Scope time(Recorder& recorder, StatName pass) override { return recorder.device(pass); }
  std::int64_t connect(const SurfaceOptions& options) override {
    return r_.connect_.run(spans_, r_.surfaces_, options.fold_step);
  }
  void filter(int iterations, const SurfaceOptions& options) override {
    r_.filter_.run(spans_, r_.surfaces_, options, iterations);
  }
  void normals(const SurfaceOptions& options) override {
    r_.normals_.run(spans_, r_.surfaces_, r_.backdrop_, r_.backdrop_given_ != nullptr,
                    options.fold_step);
  }
  void deep_ao() override { r_.deep_ao_.run(spans_, r_.surfaces_, uniforms_); }
  RefractTally shade(const ShadeOptions& options) override {
    switch (options.mode) {
      case ShadeMode::opaque:
        r_.opaque_.run(spans_, r_.surfaces_, uniforms_, r_.backdrop_, r_.image_);
        break;
      case ShadeMode::translucent:
        r_.translucent_.run(spans_, r_.surfaces_, uniforms_, r_.backdrop_, r_.image_);
        break;
      case ShadeMode::refractive:
        r_.upload_pyramid();
        return r_.refractive_.run(spans_, r_.surfaces_, uniforms_, options, r_.backdrop_,
                                  r_.image_);
    }
    return {};
  }

  Renderer& r_;
  const GpuSpanImage& spans_;
  const model::ShadeUniforms& uniforms_;
};

Renderer::Renderer(const gl::ShaderLibrary& shaders)
    : voxelizer_(shaders),
      connect_(shaders),
      filter_(shaders),
      normals_(shaders),
      deep_ao_(shaders),
      opaque_(shaders, "render/gl/passes/shade_opaque.comp"),
      translucent_(shaders, "render/gl/passes/shade_translucent.comp"),
      refractive_(shaders) {
  backdrop_.reserve(sizeof(glm::vec4));  // bound where none is used: a binding must hold one
}

void Renderer::use_backdrop(const Backdrop* backdrop) {
  backdrop_given_ = backdrop;
  if (backdrop == nullptr || backdrop->version == backdrop_version_) return;
  const std::size_t bytes = backdrop->pixels.size() * sizeof(glm::vec4);
  backdrop_.reserve(bytes);
  backdrop_.upload(backdrop->pixels.data(), bytes);
  backdrop_version_ = backdrop->version;
}

// The pyramid after the pixels, in the same buffer (the other passes read only the pixels).
void Renderer::upload_pyramid() {
  if (backdrop_given_ == nullptr || !pyramid_.update(*backdrop_given_)) return;
  const std::vector<glm::vec4>& texels = pyramid_.texels();
  const std::size_t bytes = texels.size() * sizeof(glm::vec4);
  backdrop_.reserve(bytes);
  backdrop_.upload(texels.data(), bytes);
}

const GpuFloatImage& Renderer::render(const Camera& camera,
                                      std::span<const ParticleSphere> particles,
                                      const CellStatesView& cells, const RenderOptions& options,
                                      Recorder& recorder) {
  // Options are checked before any GPU work, so a bad one costs nothing.
  validate(options.surfaces);
  validate(options.shade);
  const GpuSpanImage& spans = voxelizer_.run(camera, particles, cells, options.voxelize, recorder);
  return shade(spans, options.surfaces, options.shade, recorder);
}

const GpuFloatImage& Renderer::shade(const GpuSpanImage& spans, const SurfaceOptions& surfaces,
                                     const ShadeOptions& shade, Recorder& recorder) {
  validate(surfaces);  // before the shading's options, as render() checks them
  model::ShadeUniforms uniforms = model::shade_uniforms(shade);
  uniforms.u_use_backdrop = backdrop_given_ != nullptr ? 1 : 0;
  Passes passes(*this, spans, uniforms);
  passes.run(spans.grid(), spans.span_count() > 0, surfaces, shade, recorder);
  gl::check_error("shading a frame");
  return image_;
}

}  // namespace voxspan
