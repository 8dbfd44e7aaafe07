#include "insitu/views/scenery.h"

#include <algorithm>
#include <cmath>

#include "render/cpu/cpu_renderer.h"
#include "render/frame_units.h"
#include "render/model/shade_uniforms.h"

namespace voxspan {

const schema::Section<ScenerySettings>& scenery_section() {
  using S = ScenerySettings;
  static const schema::Section<S> s{
      "views[i].scenery",
      {schema::flag("draw", &S::draw,
                    "draw the walls and obstacles the solver gives (Adapter::set_scenery; the "
                    "offline tools: the arrays that are not fluid) as opaque solids"),
       schema::vec3("color", &S::color, "their colour, linear RGB"),
       schema::flag("cutaway", &S::cutaway,
                    "leave out the walls nearest the camera (a tank's near walls and lid), so "
                    "that the fluid inside shows")},
      [](yaml::MapReader& r, S& v) {
        if (v.color[0] < 0 || v.color[1] < 0 || v.color[2] < 0)
          r.checker().error(r.find("color"), r.path("color"), "a colour must not be negative");
      }};
  return s;
}

namespace {

// Whether world point p lies within `margin` of a face of `box`, inside it grown by `margin`.
bool on_outer_box(glm::dvec3 p, const Bounds& box, double margin) {
  double nearest = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (p[a] < box.lo[a] - margin || p[a] > box.hi[a] + margin) return false;
    nearest = std::min({nearest, std::abs(p[a] - box.lo[a]), std::abs(p[a] - box.hi[a])});
  }
  return nearest <= margin;
}

bool inside_box(glm::dvec3 p, const Bounds& box) {
  for (int a = 0; a < 3; ++a)
    if (p[a] < box.lo[a] || p[a] > box.hi[a]) return false;
  return true;
}

}  // namespace

void cut_away(const SpanImage& spans, const Bounds& box, double margin, SpanImage& out) {
  out.grid = spans.grid;
  out.pixels.resize(spans.pixels.size());
  out.spans.clear();
  const ViewFrame& view = spans.grid.view();
  // From inside the box every wall faces the camera's own room: nothing is cut.
  const bool outside = !inside_box(view.eye, box);
  for (int y = 0; y < spans.height(); ++y)
    for (int x = 0; x < spans.width(); ++x) {
      const std::span<const Span> list = spans.spans_at(x, y);
      std::size_t first = 0;
      if (outside) {
        const glm::dvec3 ray = view.world_ray(x, y);
        while (first + 1 < list.size() &&
               on_outer_box(view.eye + double(list[first].entry) * ray, box, margin))
          ++first;
      }
      PixelSpans& p = out.pixels[std::size_t(x) + std::size_t(y) * std::size_t(spans.width())];
      p.offset = static_cast<std::uint32_t>(out.spans.size());
      p.count = p.total = static_cast<std::uint32_t>(list.size() - first);
      double length = 0;
      for (std::size_t k = first; k < list.size(); ++k) {
        out.spans.push_back(list[k]);
        length += list[k].exit - list[k].entry;
      }
      p.inside = static_cast<float>(length * view.ray_scale(x, y));
    }
}

SceneryLayer::SceneryLayer(const ScenerySettings& settings, double spacing)
    : settings_(settings), spacing_(spacing) {}
SceneryLayer::~SceneryLayer() = default;

const Backdrop* SceneryLayer::backdrop(const Camera& camera,
                                       std::span<const ParticleSphere> scenery,
                                       std::uint64_t version, const Bounds& box,
                                       const ShadeOptions& shade, Recorder& recorder) {
  if (!settings_.draw || scenery.empty() || box.empty()) return nullptr;
  ShadeOptions walls = shade;
  walls.mode = ShadeMode::opaque;
  walls.deep_ao = false;
  walls.material.albedo = glm::dvec3(settings_.color[0], settings_.color[1], settings_.color[2]);
  if (backdrop_.version != 0 && camera == camera_ && version == version_ &&
      model::shade_uniforms(walls) == model::shade_uniforms(shade_))
    return &backdrop_;
  auto t = recorder.host(pass::scenery);
  render(camera, scenery, box, walls);
  camera_ = camera;
  version_ = version;
  shade_ = walls;
  ++backdrop_.version;
  return &backdrop_;
}

void SceneryLayer::render(const Camera& camera, std::span<const ParticleSphere> scenery,
                          const Bounds& box, const ShadeOptions& shade) {
  Recorder own;  // the scenery's passes are not the fluid's: timed as one, pass::scenery
  // In the frame's units, as the fluid's (render/frame_units.h); the wall depths back in world
  // units below.
  const FrameUnits u = FrameUnits::of(camera);
  std::span<const ParticleSphere> spheres = scenery;
  Bounds frame_box = box;
  if (u.scaled()) {
    u.spheres(scenery, spheres_);
    spheres = spheres_;
    for (int k = 0; k < 3; ++k) frame_box.lo[k] /= u.unit, frame_box.hi[k] /= u.unit;
  }
  SpanOptions spans;
  spans.gap_bridging = spacing_;
  float radius = 0;
  for (const ParticleSphere& s : spheres) radius = std::max(radius, s.radius);
  if (!renderer_) renderer_ = std::make_unique<CpuRenderer>();
  const SpanImage& cast = renderer_->cast(u.camera(camera), spheres, {}, u.options(spans), own);
  if (settings_.cutaway) cut_away(cast, frame_box, 1.01 * radius, drawn_);
  else drawn_ = cast;
  SurfaceOptions surfaces;
  surfaces.filter_radius = spacing_;
  renderer_->shade(drawn_, u.options(surfaces), u.options(shade), own, picture_);
  backdrop_.width = drawn_.width();
  backdrop_.height = drawn_.height();
  backdrop_.pixels.resize(std::size_t(backdrop_.width) * std::size_t(backdrop_.height));
  // The walls begin where they are drawn: at the filtered surface, not the spheres' bumps (the
  // fluid cut at those would have a dimpled face).
  const std::span<const glm::vec2> filtered = renderer_->surface_depths();
  for (int y = 0; y < backdrop_.height; ++y)
    for (int x = 0; x < backdrop_.width; ++x) {
      const PixelSpans& p = drawn_.pixel(x, y);
      float depth = Backdrop::kNoWall;
      if (p.count > 0)
        depth = static_cast<float>(
            (filtered.empty() ? drawn_.spans[p.offset].entry : filtered[p.offset].x) * u.unit);
      backdrop_.pixels[std::size_t(x) + std::size_t(y) * std::size_t(backdrop_.width)] =
          glm::vec4(glm::vec3(picture_.at(x, y)), depth);
    }
}

}  // namespace voxspan
