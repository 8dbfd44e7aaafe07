// render/gl/passes/shade_uniforms.glsl - the shading parameters the shared model files read
// (render/model/environment.glsl, lighting.glsl, shade_modes.glsl, column_march.glsl,
// deep_ao.glsl), as uniforms; render/model/shade_uniforms.h holds the same names for the CPU
// reference and sets them on a program.
uniform vec3 u_env_up;
uniform vec3 u_env_axis_a;
uniform vec3 u_env_axis_b;
uniform float u_ground_height;
uniform float u_ground_tile;
uniform vec2 u_ground_phase;
uniform float u_ground_fade;
uniform float u_ground_contact;
uniform float u_wall_contact;
uniform vec3 u_sky_zenith;
uniform vec3 u_sky_horizon;
uniform vec3 u_ground_light;
uniform vec3 u_ground_dark;
uniform vec3 u_sun_direction;
uniform vec3 u_sun_color;
uniform vec3 u_absorption;
uniform float u_ior;
uniform vec3 u_scatter_color;
uniform vec3 u_albedo;
uniform int u_use_ao;
uniform float u_ao_radius;
uniform float u_ao_strength;
uniform int u_ao_samples;
uniform int u_bounces;
uniform int u_use_backdrop;
