#include "insitu/views/surface_colors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "insitu/parallel/communicator.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

float luminance(glm::vec3 c) { return glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f)); }

// Schlick's reflectance of the water-air interface at cos_theta (render/model/lighting.glsl's).
double fresnel(double cos_theta, double ior) {
  const double f0 = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
  const double m = 1 - std::clamp(cos_theta, 0.0, 1.0);
  return f0 + (1 - f0) * m * m * m * m * m;
}

// `c` with the hue of `mapped` and its own luminance over `reference`'s: a lit surface keeps
// its light and takes the map's colour.
glm::vec3 with_hue(glm::vec3 c, glm::vec3 mapped, float reference) {
  return mapped * (luminance(c) / std::max(reference, 1e-6f));
}

}  // namespace

SurfaceColors::SurfaceColors(const ColorBySettings& settings, std::string view_name,
                             std::string key, double spacing, Communicator* comm)
    : settings_(settings),
      bar_title_(color_bar_title(settings.color_by, settings.units)),
      key_(std::move(key)),
      comm_(comm),
      color_axis_(view_name, settings.color_by, comm == nullptr || comm->root()) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw make_error("view ", view_name,
                     ": color_by needs the particle spacing (its smoothing length is 1.3 "
                     "spacings); set classification.particle_spacing or pass it to the adapter");
  quantity_.name = settings_.color_by;
  quantity_.key = key_;
  quantity_.rest_volume = spacing * spacing * spacing;
  quantity_.smoothing_length = kAutoSmoothingFactor * spacing;
  quantity_.shepard = true;
}

void SurfaceColors::sample(const ParticleView& particles, const Camera& camera,
                           const FloatImage* first_hit, const std::string& failure) {
  if (comm_ != nullptr) {
    comm_->agree_or_throw(failure.empty(), failure);
  } else if (!failure.empty()) {
    throw Error(failure);
  }
  frame_ = ViewFrame(camera);
  const std::size_t pixels = std::size_t(camera.width) * std::size_t(camera.height);
  distances_.assign(pixels, 0.0f);
  if (first_hit != nullptr)
    for (std::size_t k = 0; k < pixels; ++k) distances_[k] = first_hit->rgba[4 * k];
  if (comm_ != nullptr) {
    // The root's distances on every rank; each makes the same points from them.
    const std::string bytes = comm_->broadcast(
        comm_->root()
            ? std::string(reinterpret_cast<const char*>(distances_.data()), pixels * sizeof(float))
            : std::string());
    std::memcpy(distances_.data(), bytes.data(), std::min(bytes.size(), pixels * sizeof(float)));
  }
  point_of_.assign(pixels, -1);
  points_.clear();
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t k = std::size_t(x) + std::size_t(camera.width) * std::size_t(y);
      if (!(distances_[k] > 0)) continue;
      point_of_[k] = std::int64_t(points_.size());
      points_.push_back(frame_.eye +
                        double(distances_[k]) / frame_.ray_scale(x, y) * frame_.world_ray(x, y));
    }
  sum_ranks(particles);
  values_.resize(points_.size());
  for (std::size_t k = 0; k < points_.size(); ++k) {
    const SphSum s{sums_.sum[k], sums_.weight[k]};
    values_[k] = s.weight > 0 ? s.value(quantity_.shepard) : kNoValue;
  }
}

// This process's owned particles' sums at the points; in an MPI job the sums of every rank's.
// Every rank takes part even when its own part failed, then all throw, naming the failure.
void SurfaceColors::sum_ranks(const ParticleView& particles) {
  std::string mine;
  try {
    interpolate_at_points(particles, quantity_, points_, sums_);
  } catch (const std::exception& e) {
    mine = e.what();
  }
  if (comm_ == nullptr) {
    if (!mine.empty()) throw Error(mine);
    return;
  }
  comm_->agree_or_throw(mine.empty(), mine);
  comm_->sum(sums_.sum);
  comm_->sum(sums_.weight);
}

ColorAxis SurfaceColors::axis() const {
  ValueSpan seen;
  for (double v : values_) seen.add(v);
  return color_axis_(settings_.range, seen, settings_.scale);
}

double SurfaceColors::value(int x, int y) const {
  const std::int64_t p = point_of_[std::size_t(x) + std::size_t(frame_.width) * std::size_t(y)];
  return p < 0 ? kNoValue : values_[std::size_t(p)];
}

// The first surface's normal at pixel (x, y), facing the eye along `dir`, from the neighbours'
// first-hit points: along each axis the neighbour nearer the pixel's point, so that a
// silhouette's far side does not tilt it; -dir where no neighbour is hit.
glm::dvec3 SurfaceColors::normal_at(int x, int y, glm::dvec3 dir) const {
  const auto point = [&](int i, int j) -> const glm::dvec3* {
    if (i < 0 || j < 0 || i >= frame_.width || j >= frame_.height) return nullptr;
    const std::int64_t p = point_of_[std::size_t(i) + std::size_t(frame_.width) * std::size_t(j)];
    return p < 0 ? nullptr : &points_[std::size_t(p)];
  };
  const glm::dvec3 c = *point(x, y);
  const auto tangent = [&](int dx, int dy) {
    const glm::dvec3 *a = point(x - dx, y - dy), *b = point(x + dx, y + dy);
    if (a != nullptr && b != nullptr)
      return glm::dot(*a - c, *a - c) < glm::dot(*b - c, *b - c) ? c - *a : *b - c;
    return b != nullptr ? *b - c : a != nullptr ? c - *a : glm::dvec3(0);
  };
  glm::dvec3 n = glm::cross(tangent(1, 0), tangent(0, 1));
  const double length = glm::length(n);
  if (!(length > 0)) return -dir;
  n /= length;
  return glm::dot(n, dir) > 0 ? -n : n;
}

// The share pixel (x, y)'s first surface reflects over its footprint, as the shading averages its
// Fresnel term over the pixels a surface point links to (render/model/shade_modes.glsl,
// reflection_footprint): here the mean of fresnel_ at the pixel and its coloured neighbours (a
// crest's rim otherwise beads into dots).
double SurfaceColors::reflectance(int x, int y) const {
  double sum = 0;
  int n = 0;
  for (int k = 0; k < 5; ++k) {
    const int i = x + (k == 1) - (k == 2), j = y + (k == 3) - (k == 4);
    if (i < 0 || j < 0 || i >= frame_.width || j >= frame_.height || std::isnan(value(i, j)))
      continue;
    sum += fresnel_[std::size_t(
        point_of_[std::size_t(i) + std::size_t(frame_.width) * std::size_t(j)])];
    ++n;
  }
  return sum / n;  // n >= 1: (x, y) itself is coloured
}

// The luminance that shows the map's colours as they are: the albedo's for an opaque surface (the
// map's colour times the lighting), else the mean of the coloured pixels' (the light the fluid
// sends back varies with what lies behind it: so it keeps its variations and the map its
// colours).
float SurfaceColors::reference_luminance(const ShadeOptions& shade,
                                         const FloatImage& picture) const {
  if (shade.mode == ShadeMode::opaque) return luminance(glm::vec3(shade.material.albedo));
  double sum = 0;
  std::size_t count = 0;
  for (int y = 0; y < picture.height; ++y)
    for (int x = 0; x < picture.width; ++x)
      if (!std::isnan(value(x, y))) sum += luminance(glm::vec3(picture.at(x, y))), ++count;
  return count > 0 ? float(sum / double(count)) : 1.0f;
}

void SurfaceColors::paint(const ShadeOptions& shade, FloatImage& picture, BarSide side) const {
  const ColorAxis axis = this->axis();
  const float reference = reference_luminance(shade, picture);
  if (shade.mode != ShadeMode::opaque) {
    fresnel_.resize(points_.size());
    for (int y = 0; y < frame_.height; ++y)
      for (int x = 0; x < frame_.width; ++x) {
        const std::int64_t p =
            point_of_[std::size_t(x) + std::size_t(frame_.width) * std::size_t(y)];
        if (p < 0) continue;
        const glm::dvec3 dir = glm::normalize(frame_.world_ray(x, y));
        fresnel_[std::size_t(p)] =
            fresnel(-glm::dot(dir, normal_at(x, y, dir)), shade.material.ior);
      }
  }
  for (int y = 0; y < picture.height; ++y)
    for (int x = 0; x < picture.width; ++x) {
      const double v = value(x, y);
      if (std::isnan(v)) continue;
      const glm::vec3 mapped = map_color(settings_.color_map, axis.t(v));
      const glm::vec4 c = picture.at(x, y);
      const glm::vec3 shaded(c);
      glm::vec3 out;
      if (shade.mode == ShadeMode::opaque) {
        out = with_hue(shaded, mapped, reference);
      } else {
        const float r = float(reflectance(x, y));
        out = r * shaded + (1 - r) * with_hue(shaded, mapped, reference);
      }
      picture.set(x, y, glm::vec4(out, c.a));
    }
  if (settings_.legend) draw_color_bar(picture, settings_.color_map, axis, bar_title_, side);
}

}  // namespace voxspan
