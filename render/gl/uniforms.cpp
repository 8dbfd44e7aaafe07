#include "render/gl/uniforms.h"

namespace voxspan {

void set_grid_uniforms(const gl::Program& program, const PerspectiveGrid& grid) {
  const ViewFrame& v = grid.view();
  program.set("u_eye", glm::vec3(v.eye));
  program.set("u_right", glm::vec3(v.right));
  program.set("u_up", glm::vec3(v.up));
  program.set("u_forward", glm::vec3(v.forward));
  program.set("u_tan_half", glm::vec2(float(v.tan_half_x), float(v.tan_half_y)));
  program.set("u_image", glm::ivec2(v.width, v.height));
  program.set("u_near", float(grid.near()));
  program.set("u_log2_step", float(grid.log2_step()));
  program.set("u_inv_log2_step", grid.empty() ? 0.0f : float(1.0 / grid.log2_step()));
  program.set("u_layers", static_cast<unsigned>(grid.layers()));
  program.set("u_grid_far", float(grid.grid_far()));
}

void set_shade_uniforms(const gl::Program& p, const model::ShadeUniforms& u) {
  p.set("u_env_up", u.u_env_up);
  p.set("u_env_axis_a", u.u_env_axis_a);
  p.set("u_env_axis_b", u.u_env_axis_b);
  p.set("u_ground_height", u.u_ground_height);
  p.set("u_ground_tile", u.u_ground_tile);
  p.set("u_ground_phase", u.u_ground_phase);
  p.set("u_ground_contact", u.u_ground_contact);
  p.set("u_wall_contact", u.u_wall_contact);
  p.set("u_ground_fade", u.u_ground_fade);
  p.set("u_sky_zenith", u.u_sky_zenith);
  p.set("u_sky_horizon", u.u_sky_horizon);
  p.set("u_ground_light", u.u_ground_light);
  p.set("u_ground_dark", u.u_ground_dark);
  p.set("u_sun_direction", u.u_sun_direction);
  p.set("u_sun_color", u.u_sun_color);
  p.set("u_absorption", u.u_absorption);
  p.set("u_ior", u.u_ior);
  p.set("u_scatter_color", u.u_scatter_color);
  p.set("u_albedo", u.u_albedo);
  p.set("u_use_ao", u.u_use_ao);
  p.set("u_ao_radius", u.u_ao_radius);
  p.set("u_ao_strength", u.u_ao_strength);
  p.set("u_ao_samples", u.u_ao_samples);
  p.set("u_bounces", u.u_bounces);
  p.set("u_use_backdrop", u.u_use_backdrop);
}

}  // namespace voxspan
