#include "render/renderer.h"

namespace voxspan {

Renderer::Renderer(const gl::ShaderLibrary& shaders)
    : voxelizer_(shaders),
      connect_(shaders),
      filter_(shaders),
      normals_(shaders),
      deep_ao_(shaders),
      opaque_(shaders, "render/passes/shade_opaque.comp"),
      translucent_(shaders, "render/passes/shade_translucent.comp"),
      refractive_(shaders) {}

const GpuFloatImage& Renderer::render(const Camera& camera,
                                      std::span<const ParticleSphere> particles,
                                      const CellStatesView& cells, const RenderOptions& options,
                                      gl::PassTimer& timer, FrameStats& stats) {
  // Options are checked before any GPU work, so a bad one costs nothing.
  validate(options.surfaces);
  validate(options.shade);
  const GpuSpanImage& spans =
      voxelizer_.run(camera, particles, cells, options.voxelize, timer, stats);
  return shade(spans, options.surfaces, options.shade, timer, stats);
}

const GpuFloatImage& Renderer::shade(const GpuSpanImage& spans, const SurfaceOptions& surfaces,
                                     const ShadeOptions& shade, gl::PassTimer& timer,
                                     FrameStats& stats) {
  validate(surfaces);
  const model::ShadeUniforms uniforms = model::shade_uniforms(shade);
  {
    auto t = timer.gpu("connect");
    stats.set_count("links.unlinkable_spans", connect_.run(spans, surfaces_));
  }
  {
    auto t = timer.gpu("filter");
    stats.set_count("filter.iterations", filter_.run(spans, surfaces_, surfaces));
  }
  {
    auto t = timer.gpu("normals");
    normals_.run(spans, surfaces_);
  }
  if (shade.deep_ao) {
    auto t = timer.gpu("deep_ao");
    deep_ao_.run(spans, surfaces_, uniforms);
  }
  auto t = timer.gpu("shade");
  switch (shade.mode) {
    case ShadeMode::opaque: opaque_.run(spans, surfaces_, uniforms, image_); break;
    case ShadeMode::translucent: translucent_.run(spans, surfaces_, uniforms, image_); break;
    case ShadeMode::refractive: {
      const RefractTally tally = refractive_.run(spans, surfaces_, uniforms, shade, image_);
      stats.set_count("refract.dispatches", tally.dispatches);
      stats.set_count("refract.unfinished", tally.unfinished);
      stats.set_count("refract.events", tally.events);
      stats.set_count("refract.most_events", tally.most_events);
      break;
    }
  }
  gl::check_error("shading a frame");
  return image_;
}

}  // namespace voxspan
