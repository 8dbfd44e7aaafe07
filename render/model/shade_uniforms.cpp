#include "render/model/shade_uniforms.h"

#include <cmath>

namespace voxspan::model {

ShadeUniforms shade_uniforms(const ShadeOptions& o) {
  validate(o);
  const Environment& e = o.environment;
  ShadeUniforms u;
  const glm::dvec3 up = glm::normalize(e.up);
  // Ground axes: any orthonormal pair across `up`, from the world axis least aligned with it.
  const glm::dvec3 seed = std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
  const glm::dvec3 a = glm::normalize(glm::cross(seed, up));
  u.u_env_up = vec3(up);
  u.u_env_axis_a = vec3(a);
  u.u_env_axis_b = vec3(glm::cross(up, a));
  // The plane and the checker in the frame's coordinates (Environment::origin), from world
  // coordinates in double: at 4.2e6 a float would round the shift to 0.5.
  u.u_ground_height = float(e.ground_height - glm::dot(e.origin, up));
  u.u_ground_tile = float(e.ground_tile);
  u.u_ground_phase =
      vec2(float(std::fmod(glm::dot(e.origin, a) / e.ground_tile, 2.0)),
           float(std::fmod(glm::dot(e.origin, glm::cross(up, a)) / e.ground_tile, 2.0)));
  u.u_ground_contact = float(e.ground_contact);
  u.u_wall_contact = float(e.wall_contact);
  u.u_ground_fade = float(e.ground_fade > 0 ? e.ground_fade : 40 * e.ground_tile);
  u.u_sky_zenith = vec3(e.sky_zenith);
  u.u_sky_horizon = vec3(e.sky_horizon);
  u.u_ground_light = vec3(e.ground_light);
  u.u_ground_dark = vec3(e.ground_dark);
  u.u_sun_direction = vec3(glm::normalize(e.sun_direction));
  u.u_sun_color = vec3(e.sun_color);
  const Material& m = o.material;
  u.u_absorption = vec3(m.absorption);
  u.u_ior = float(m.ior);
  u.u_scatter_color = vec3(m.scatter_color);
  u.u_albedo = vec3(m.albedo);
  u.u_use_ao = o.deep_ao ? 1 : 0;
  u.u_ao_radius = float(o.ao.radius);
  u.u_ao_strength = float(o.ao.strength);
  u.u_ao_samples = o.ao.samples;
  u.u_bounces = o.bounces;
  return u;
}

GridUniforms grid_uniforms(const PerspectiveGrid& grid) {
  const ViewFrame& v = grid.view();
  GridUniforms g;
  g.u_eye = vec3(v.eye);
  g.u_right = vec3(v.right);
  g.u_up = vec3(v.up);
  g.u_forward = vec3(v.forward);
  g.u_tan_half = vec2(float(v.tan_half_x), float(v.tan_half_y));
  g.u_image = ivec2(v.width, v.height);
  g.u_near = float(grid.near());
  g.u_grid_far = float(grid.grid_far());
  g.u_log2_step = float(grid.log2_step());
  return g;
}

}  // namespace voxspan::model
