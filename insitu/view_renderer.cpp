#include "insitu/view_renderer.h"

#include <algorithm>
#include <cmath>

#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

// The picture from the span image alone, until the shading passes are on this branch:
// Beer-Lambert absorption over the exact inside length of every pixel (sec. 3.5's
// translucency without Fresnel or normals) in front of a sky gradient.
void shade_inside_length(std::span<const PixelSpans> pixels, int width, int height,
                         const Vec3d& absorption, std::vector<float>& rgba) {
  const float zenith[3] = {0.22f, 0.42f, 0.8f}, horizon[3] = {0.78f, 0.84f, 0.9f};
  const float scatter[3] = {0.02f, 0.06f, 0.09f};
  for (int y = 0; y < height; ++y) {
    const float t = float(y) / float(std::max(height - 1, 1));
    for (int x = 0; x < width; ++x) {
      const std::size_t p = std::size_t(x) + std::size_t(y) * std::size_t(width);
      const float inside = pixels[p].inside;
      float* out = &rgba[4 * p];
      for (int c = 0; c < 3; ++c) {
        const float sky = zenith[c] + (horizon[c] - zenith[c]) * t;
        const float transmit = std::exp(-float(absorption[std::size_t(c)]) * inside);
        out[c] = sky * transmit + scatter[c] * (1 - transmit);
      }
      out[3] = 1;
    }
  }
}

}  // namespace

ViewRenderSettings view_render_settings(const ViewConfig& view, const RendererConfig& renderer,
                                        double spacing) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw make_error("view ", view.name, ": the particle spacing (", spacing,
                     ") is needed for the automatic gap and filter radius; set "
                     "classification.particle_spacing or the view's gap and filter_radius");
  ViewRenderSettings s;
  s.voxelize.grid.alpha_degrees = view.alpha_degrees;
  s.voxelize.grid.max_layers = view.max_layers;
  s.voxelize.gap_bridging = view.gap.value_or(spacing);
  s.voxelize.max_spans = static_cast<std::uint32_t>(view.max_spans);
  s.voxelize.tiles.memory_budget = static_cast<std::size_t>(renderer.gpu_memory_mib * kMiB);
  s.shading = view.shading;
  s.deep_ao = view.deep_ao;
  s.filter_radius = view.filter_radius.value_or(spacing);
  s.absorption = view.absorption;
  s.ior = view.ior;
  s.bounces = view.bounces;
  s.up = view.camera.up;
  validate(s.voxelize);
  return s;
}

ViewRenderer::ViewRenderer(const gl::ShaderLibrary& shaders) : voxelizer_(shaders) {}

void ViewRenderer::render(const ViewRenderSettings& settings, const Camera& camera,
                          const Bounds& /*fluid_box*/, std::span<const ParticleSphere> boundary,
                          const CellStatesView& cells, gl::PassTimer& timer, FrameStats& stats,
                          ViewImage& out) {
  const GpuSpanImage& spans =
      voxelizer_.run(camera, boundary, cells, settings.voxelize, timer, stats);
  out.width = camera.width;
  out.height = camera.height;
  const std::size_t count = std::size_t(out.width) * std::size_t(out.height);
  out.rgba.resize(4 * count);
  pixels_.resize(count);
  {
    auto t = timer.gpu("readback");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the compress pass wrote them in a shader
    spans.pixels().download(pixels_.data(), count * sizeof(PixelSpans));
  }
  auto t = timer.cpu("shade");
  shade_inside_length(pixels_, out.width, out.height, settings.absorption, out.rgba);
}

}  // namespace voxspan
