#include "render/frame_units.h"

#include <cmath>

namespace voxspan {
namespace {

// Cameras from 2^-32 to 2^32 world units from their target render as given: at unit scale
// the passes' squares of lengths are far from float's bounds either way (pictures from 1e-12
// to 1e16 matched the unit scene's before frames were rescaled), and such frames copy nothing.
constexpr int kUnscaledExponent = 32;

float times(float v, double factor) { return static_cast<float>(double(v) * factor); }

// `in` with its depths and lengths times `factor` (a power of two: exact), seen from `camera`.
void rescale(const SpanImage& in, const Camera& camera, double factor, SpanImage& out) {
  out.grid = in.grid.rescaled(camera, factor);
  out.pixels = in.pixels;
  for (PixelSpans& p : out.pixels) p.inside = times(p.inside, factor);
  out.spans.resize(in.spans.size());
  for (std::size_t i = 0; i < in.spans.size(); ++i)
    out.spans[i] = {times(in.spans[i].entry, factor), times(in.spans[i].exit, factor)};
}

}  // namespace

FrameUnits FrameUnits::of(const Camera& camera) {
  const double distance = glm::length(camera.target - camera.eye);
  FrameUnits u;
  if (!(distance > 0) || !std::isfinite(distance)) return u;  // validate(camera) says why
  const int exponent = static_cast<int>(std::lround(std::log2(distance)));
  if (std::abs(exponent) > kUnscaledExponent) u.unit = std::ldexp(1.0, exponent);
  return u;
}

Camera FrameUnits::camera(const Camera& world) const {
  Camera c = world;
  c.eye = world.eye / unit;
  c.target = world.target / unit;
  return c;
}

CellStatesView FrameUnits::cells(const CellStatesView& world) const {
  CellStatesView c = world;
  for (double& o : c.origin) o /= unit;
  c.cell_size /= unit;
  return c;
}

void FrameUnits::spheres(std::span<const ParticleSphere> world,
                         std::vector<ParticleSphere>& out) const {
  const double f = 1 / unit;
  out.resize(world.size());
  for (std::size_t i = 0; i < world.size(); ++i) {
    const ParticleSphere& p = world[i];
    out[i] = {times(p.x, f), times(p.y, f), times(p.z, f), times(p.radius, f)};
  }
}

SpanOptions FrameUnits::options(const SpanOptions& world) const {
  SpanOptions o = world;
  o.grid.min_near = length(world.grid.min_near);
  o.gap_bridging = length(world.gap_bridging);
  o.unit = world.unit * unit;
  return o;
}

SurfaceOptions FrameUnits::options(const SurfaceOptions& world) const {
  SurfaceOptions o = world;
  o.filter_radius = length(world.filter_radius);
  o.fold_step = length(world.fold_step);
  return o;
}

ShadeOptions FrameUnits::options(const ShadeOptions& world) const {
  ShadeOptions o = world;
  o.material.absorption = world.material.absorption * unit;
  Environment& e = o.environment;
  // The ground plane dot(x, up) = h holds for x / unit at h / unit, whatever up's length.
  e.origin /= unit;
  e.ground_height = length(e.ground_height);
  e.ground_tile = length(e.ground_tile);
  e.ground_fade = length(e.ground_fade);
  e.ground_contact = length(e.ground_contact);
  e.wall_contact = length(e.wall_contact);
  o.ao.radius = length(world.ao.radius);
  return o;
}

void FrameUnits::to_world(const SpanImage& frame, const Camera& world, SpanImage& out) const {
  rescale(frame, world, unit, out);
}

void FrameUnits::to_frame(const SpanImage& world, SpanImage& out) const {
  rescale(world, camera(world.grid.camera()), 1 / unit, out);
}

void FrameUnits::to_frame(const Backdrop& world, Backdrop& out) const {
  out.width = world.width;
  out.height = world.height;
  out.pixels = world.pixels;
  for (glm::vec4& p : out.pixels)
    if (p.a != Backdrop::kNoWall) p.a = times(p.a, 1 / unit);
}

namespace {

class FrameUnitsRenderer final : public SurfaceRenderer {
 public:
  explicit FrameUnitsRenderer(std::unique_ptr<SurfaceRenderer> inner) : inner_(std::move(inner)) {}

  void make_spans(const Camera& camera, std::span<const ParticleSphere> particles,
                  const CellStatesView& cells, const SpanOptions& options,
                  Recorder& recorder) override {
    units_ = FrameUnits::of(camera);
    camera_ = camera;
    if (!units_.scaled()) return inner_->make_spans(camera, particles, cells, options, recorder);
    units_.spheres(particles, spheres_);
    inner_->make_spans(units_.camera(camera), spheres_, units_.cells(cells),
                       units_.options(options), recorder);
  }
  const SpanImage& host_spans(StatName pass, Recorder& recorder) override {
    const SpanImage& spans = inner_->host_spans(pass, recorder);
    if (!units_.scaled()) return spans;
    units_.to_world(spans, camera_, world_spans_);
    return world_spans_;
  }
  void use_spans(const SpanImage& spans, StatName pass, Recorder& recorder) override {
    if (!units_.scaled()) return inner_->use_spans(spans, pass, recorder);
    units_.to_frame(spans, frame_spans_);
    inner_->use_spans(frame_spans_, pass, recorder);
  }
  void shade(const SurfaceOptions& surfaces, const ShadeOptions& shade, Recorder& recorder,
             FloatImage& picture) override {
    if (!units_.scaled()) return inner_->shade(surfaces, shade, recorder, picture);
    inner_->shade(units_.options(surfaces), units_.options(shade), recorder, picture);
  }
  PendingPicture* shade_later(const SurfaceOptions& surfaces, const ShadeOptions& shade,
                              Recorder& recorder, FloatImage& picture, ReadLater when) override {
    if (!units_.scaled()) return inner_->shade_later(surfaces, shade, recorder, picture, when);
    return inner_->shade_later(units_.options(surfaces), units_.options(shade), recorder, picture,
                               when);
  }
  bool packs_srgb8(ReadLater when) const override { return inner_->packs_srgb8(when); }
  PendingPicture* shade_srgb8_later(const SurfaceOptions& surfaces, const ShadeOptions& shade,
                                    Recorder& recorder, ImageRGBA8& picture,
                                    ReadLater when) override {
    if (!units_.scaled())
      return inner_->shade_srgb8_later(surfaces, shade, recorder, picture, when);
    return inner_->shade_srgb8_later(units_.options(surfaces), units_.options(shade), recorder,
                                     picture, when);
  }
  // Given after the frame's spans, whose units it takes.
  void use_backdrop(const Backdrop* backdrop, Recorder& recorder) override {
    if (!units_.scaled() || backdrop == nullptr) return inner_->use_backdrop(backdrop, recorder);
    units_.to_frame(*backdrop, frame_backdrop_);
    // Its own versions: the same world backdrop in other units is another picture.
    frame_backdrop_.version = kOwnVersions | ++conversions_;
    inner_->use_backdrop(&frame_backdrop_, recorder);
  }
  void first_hit(Recorder& recorder, FloatImage& out, HitSurface surface) override {
    inner_->first_hit(recorder, out, surface);
    if (!units_.scaled()) return;
    for (std::size_t k = 0; k < out.rgba.size(); k += 4)
      out.rgba[k] = static_cast<float>(double(out.rgba[k]) * units_.unit);
  }

 private:
  static constexpr std::uint64_t kOwnVersions = std::uint64_t(1) << 63;

  std::unique_ptr<SurfaceRenderer> inner_;
  FrameUnits units_;
  Camera camera_;                        // the frame's, in world units
  std::vector<ParticleSphere> spheres_;  // the frame's spheres in frame units, when scaled
  SpanImage world_spans_, frame_spans_;  // span images converted out and in
  Backdrop frame_backdrop_;
  std::uint64_t conversions_ = 0;
};

}  // namespace

std::unique_ptr<SurfaceRenderer> in_frame_units(std::unique_ptr<SurfaceRenderer> renderer) {
  return std::make_unique<FrameUnitsRenderer>(std::move(renderer));
}

}  // namespace voxspan
