#include "render/shade_options.h"

#include <algorithm>
#include <cmath>

#include "voxspan/error.h"

namespace voxspan {
namespace {

bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_color(const char* name, glm::dvec3 v) {
  if (!finite(v) || v.x < 0 || v.y < 0 || v.z < 0)
    throw make_error(name, " = (", v.x, ", ", v.y, ", ", v.z, ") must be finite and >= 0");
}

void check_direction(const char* name, glm::dvec3 v) {
  if (!finite(v) || !(glm::length(v) > 0))
    throw make_error(name, " = (", v.x, ", ", v.y, ", ", v.z,
                     ") must be a finite, non-zero vector");
}

}  // namespace

int refract_dispatch_limit(int width, int height, std::uint32_t most_spans, const ShadeOptions& o) {
  const long long events = 2LL * (width + height + 2LL * most_spans) * (o.bounces + 2);
  return static_cast<int>(std::min<long long>(events / std::max(o.march_budget, 1) + 8, 1 << 20));
}

void validate(const SurfaceOptions& o) {
  if (!std::isfinite(o.filter_radius) || o.filter_radius < 0)
    throw make_error("filter_radius = ", o.filter_radius, " must be a finite number >= 0");
  if (!(o.max_screen_radius > 0 && o.max_screen_radius <= 0.5))
    throw make_error("filter max_screen_radius = ", o.max_screen_radius,
                     " is outside (0, 0.5] of the picture's height");
  if (!std::isfinite(o.fold_step) || o.fold_step < 0)
    throw make_error("fold_step = ", o.fold_step, " must be a finite number >= 0");
}

glm::dvec3 Material::water_absorption(double depth) {
  const glm::dvec3 water = Material{}.absorption;
  return water * (std::log(10.0) / (water.r * depth));
}

void validate(const ShadeOptions& o) {
  const Material& m = o.material;
  check_color("absorption", m.absorption);
  check_color("scatter_color", m.scatter_color);
  check_color("albedo", m.albedo);
  if (!(m.ior >= 1 && m.ior <= 4)) throw make_error("ior = ", m.ior, " is outside [1, 4]");
  const Environment& e = o.environment;
  check_direction("environment up", e.up);
  check_direction("environment sun_direction", e.sun_direction);
  if (!std::isfinite(e.origin.x) || !std::isfinite(e.origin.y) || !std::isfinite(e.origin.z))
    throw make_error("environment origin is not finite");
  if (!std::isfinite(e.ground_height))
    throw make_error("environment ground_height = ", e.ground_height, " is not finite");
  if (!(e.ground_tile > 0) || !std::isfinite(e.ground_tile))
    throw make_error("environment ground_tile = ", e.ground_tile, " must be > 0");
  if (!(e.ground_contact >= 0) || !std::isfinite(e.ground_contact))
    throw make_error("environment ground_contact = ", e.ground_contact, " must be >= 0");
  if (!(e.ground_fade >= 0) || !std::isfinite(e.ground_fade))
    throw make_error("environment ground_fade = ", e.ground_fade, " must be >= 0 (0 = 40 tiles)");
  for (auto [name, c] : {std::pair{"sky_zenith", e.sky_zenith},
                         {"sky_horizon", e.sky_horizon},
                         {"ground_light", e.ground_light},
                         {"ground_dark", e.ground_dark},
                         {"sun_color", e.sun_color}})
    check_color(name, c);
  if (!(o.ao.radius > 0) || !std::isfinite(o.ao.radius))
    throw make_error("ao radius = ", o.ao.radius, " must be > 0");
  if (!(o.ao.strength >= 0) || !std::isfinite(o.ao.strength))
    throw make_error("ao strength = ", o.ao.strength, " must be >= 0");
  if (o.ao.samples < 1 || o.ao.samples > 64)
    throw make_error("ao samples = ", o.ao.samples, " is outside 1..64");
  if (o.bounces < 0 || o.bounces > 16)
    throw make_error("bounces = ", o.bounces, " is outside 0..16");
  if (o.march_budget < 1 || o.march_budget > 1024)
    throw make_error("march_budget = ", o.march_budget, " is outside 1..1024");
}

}  // namespace voxspan
