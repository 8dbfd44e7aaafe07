// render/model/shade_uniforms.h - the shading parameters as the shared model files read them
// (u_* names; render/gl/passes/shade_uniforms.glsl declares the same uniforms for the GPU), made
// from ShadeOptions once, set on GPU programs (render/gl/uniforms.h) or held by the host
// (render/model/host.h).
#pragma once

#include "render/model/glsl_cpp.h"
#include "render/perspective_grid.h"
#include "render/shade_options.h"

namespace voxspan::model {

struct ShadeUniforms {
  vec3 u_env_up{0.0f, 1.0f, 0.0f}, u_env_axis_a{1.0f, 0.0f, 0.0f}, u_env_axis_b{0.0f, 0.0f, 1.0f};
  float u_ground_height = 0.0f, u_ground_tile = 1.0f, u_ground_fade = 1.0f, u_ground_contact = 0.0f;
  vec2 u_ground_phase{0.0f};  // the checker's (a, b) at the frame's origin, in tiles, mod 2
  float u_wall_contact = 0.0f;
  vec3 u_sky_zenith{0.0f}, u_sky_horizon{0.0f}, u_ground_light{0.0f}, u_ground_dark{0.0f};
  vec3 u_sun_direction{0.0f, 1.0f, 0.0f}, u_sun_color{0.0f};
  vec3 u_absorption{0.0f};
  float u_ior = 1.0f;
  vec3 u_scatter_color{0.0f}, u_albedo{0.0f};
  int u_use_ao = 0;
  float u_ao_radius = 1.0f, u_ao_strength = 0.0f;
  int u_ao_samples = 1;
  int u_bounces = 0;
  // 1: a backdrop (render/backdrop.h) stands behind the fluid: sd_backdrop() per pixel; set by
  // the renderer that has one, not by the options.
  int u_use_backdrop = 0;
  bool operator==(const ShadeUniforms&) const = default;
};

// Validates `options` (voxspan::Error naming the option).
ShadeUniforms shade_uniforms(const ShadeOptions& options);

// render/gl/perspective_grid.glsl's uniforms for the CPU host, as set_grid_uniforms() sets them.
GridUniforms grid_uniforms(const PerspectiveGrid& grid);

}  // namespace voxspan::model
