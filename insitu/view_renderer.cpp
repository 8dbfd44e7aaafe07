#include "insitu/view_renderer.h"

#include <algorithm>
#include <cmath>

#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

glm::dvec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

ShadeMode shade_mode(ShadingMode mode) {
  switch (mode) {
    case ShadingMode::opaque: return ShadeMode::opaque;
    case ShadingMode::translucent: return ShadeMode::translucent;
    case ShadingMode::refractive: return ShadeMode::refractive;
  }
  return ShadeMode::translucent;
}

// Towards the sun: mostly up, a little to two sides, whatever axis is up.
glm::dvec3 sun_direction(glm::dvec3 up) {
  up = glm::normalize(up);
  const glm::dvec3 other = std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 a = glm::normalize(glm::cross(up, other)), b = glm::cross(up, a);
  return up + 0.35 * a + 0.45 * b;
}

// The lowest point of the box along `up`: the ground plane lies there.
double lowest(const Bounds& box, glm::dvec3 up) {
  up = glm::normalize(up);
  double low = 1e300;
  for (int k = 0; k < 8; ++k)
    low = std::min(low, glm::dot(up, glm::dvec3(k & 1 ? box.hi[0] : box.lo[0],
                                                 k & 2 ? box.hi[1] : box.lo[1],
                                                 k & 4 ? box.hi[2] : box.lo[2])));
  return low;
}

}  // namespace

ViewRenderSettings view_render_settings(const ViewConfig& view, const RendererConfig& renderer,
                                        double spacing) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw make_error("view ", view.name, ": the particle spacing (", spacing,
                     ") is needed for the view's automatic settings; set "
                     "classification.particle_spacing or pass it to the adapter");
  ViewRenderSettings s;
  VoxelizeOptions& v = s.render.voxelize;
  v.grid.alpha_degrees = view.alpha_degrees;
  v.grid.max_layers = view.max_layers;
  v.gap_bridging = view.gap.value_or(spacing);
  v.max_spans = static_cast<std::uint32_t>(view.max_spans);
  v.tiles.memory_budget = static_cast<std::size_t>(renderer.gpu_memory_mib * kMiB);
  s.render.surfaces.filter_radius = view.filter_radius.value_or(spacing);
  ShadeOptions& shade = s.render.shade;
  shade.mode = shade_mode(view.shading);
  shade.deep_ao = view.deep_ao;
  shade.ao.radius = 4 * spacing;
  shade.material.absorption = vec(view.absorption);
  shade.material.ior = view.ior;
  shade.bounces = view.bounces;
  shade.environment.up = vec(view.camera.up);
  shade.environment.sun_direction = sun_direction(shade.environment.up);
  shade.environment.ground_tile = 12 * spacing;
  validate(v);
  validate(s.render.surfaces);
  validate(shade);
  return s;
}

ViewRenderer::ViewRenderer(const gl::ShaderLibrary& shaders) : renderer_(shaders) {}

void ViewRenderer::render(const ViewRenderSettings& settings, const Camera& camera,
                          const Bounds& fluid_box, std::span<const ParticleSphere> boundary,
                          const CellStatesView& cells, gl::PassTimer& timer, FrameStats& stats,
                          ViewImage& out) {
  options_ = settings.render;
  if (!fluid_box.empty())
    options_.shade.environment.ground_height = lowest(fluid_box, options_.shade.environment.up);
  const GpuFloatImage& image = renderer_.render(camera, boundary, cells, options_, timer, stats);
  auto t = timer.gpu("readback");
  image.download(out);
}

}  // namespace voxspan
