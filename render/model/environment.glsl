// render/model/environment.glsl - what surrounds the fluid: a sky gradient with a soft sun glow and
// an infinite ground plane with a checker pattern fading into the horizon, so that reflections and
// refractions show where the light comes from ([ZD15] sec. 3.5). Shared by the GPU shading passes
// and the C++ host (render/model/host.h: the CPU renderer and the reference). All world space.
//
// Host needs uniforms: u_env_up (unit, the sky's direction), u_env_axis_a, u_env_axis_b (unit,
// the ground's tangent axes), u_ground_height (the plane dot(x, up) = height), u_ground_tile
// (checker side, world units), u_ground_phase (the checker's phase at the frame's origin, in
// tiles: a frame shifted from the world's origin keeps the world's checker), u_ground_fade (distance over which the pattern fades),
// u_sky_zenith, u_sky_horizon, u_ground_light, u_ground_dark, u_sun_direction (unit, towards the
// sun), u_sun_color.
#ifndef VX_MODEL_ENVIRONMENT
#define VX_MODEL_ENVIRONMENT

vec3 sky_color(vec3 dir) {
  float h = clamp(dot(dir, u_env_up), 0.0f, 1.0f);
  vec3 sky = mix(u_sky_horizon, u_sky_zenith, sqrt(h));
  float glow = max(dot(dir, u_sun_direction), 0.0f);
  return sky + u_sun_color * (0.2f * pow(glow, 32.0f));
}

// A square wave with edges softened over about a twentieth of a tile, so the pattern stays
// calm under small changes of the rays that sample it: clamp(4 sin(pi u), -1, 1), whose sine
// only matters within asin(1/4) / pi = 0.0804 of an integer; elsewhere the sign alone decides
// (most of the ground: on the CPU renderer the sines were 60 % of the environment's time).
float soft_square(float u) {
  float f = fract(u);
  float side = mod(floor(u), 2.0f) == 0.0f ? 1.0f : -1.0f;
  if (f > 0.081f && f < 0.919f) return side;
  return side * clamp(4.0f * sin(3.14159265f * f), -1.0f, 1.0f);
}

// The square wave's mean over [u - w / 2, u + w / 2]: its integral, a triangle wave, differenced.
// Past the soft edges' own width it is the edges' mean where neighbouring rays spread wider than
// they: a checker seen over a footprint of w tiles, not one point of it.
float square_integral(float u) {
  float f = mod(u, 2.0f);
  return f < 1.0f ? f : 2.0f - f;
}
float square_over(float u, float w) {
  if (w <= 0.16f) return soft_square(u);  // 2 x 0.0804: soft_square's edges, which it matches
  return (square_integral(u + 0.5f * w) - square_integral(u - 0.5f * w)) / w;
}

// The ground at `hit`, `distance` from where it is seen, over a footprint `width` wide (world).
vec3 ground_color(vec3 hit, float distance, float width) {
  float a = dot(hit, u_env_axis_a) / u_ground_tile + u_ground_phase.x;
  float b = dot(hit, u_env_axis_b) / u_ground_tile + u_ground_phase.y;
  float w = width / u_ground_tile;
  float checker = 0.5f + 0.5f * square_over(a, w) * square_over(b, w);
  vec3 ground = mix(u_ground_dark, u_ground_light, checker);
  float fade = 1.0f - exp(-distance / u_ground_fade);
  return mix(ground, u_sky_horizon, fade);
}

// The ground seen from `origin` along `dir` (unit, below the horizon), over a cone `spread`
// radians wide: its footprint 2 t spread wide, stretched by the grazing angle (up to 16 times:
// past that the horizon's fade has taken the pattern).
vec3 ground_over(vec3 origin, vec3 dir, float spread) {
  float down = dot(dir, u_env_up);
  // Seen from above (from below the plane, where it lies).
  float t = max((u_ground_height - dot(origin, u_env_up)) / down, 0.0f);
  return ground_color(origin + t * dir, t, 2.0f * t * spread / max(-down, 0.0625f));
}

// `dir` turned about the horizontal towards elevation `e` (radians).
vec3 at_elevation(vec3 dir, float e) {
  vec3 level = dir - dot(dir, u_env_up) * u_env_up;
  float len = length(level);
  level = len > 1e-6f ? level / len : u_env_axis_a;
  return cos(e) * level + sin(e) * u_env_up;
}

// Radiance arriving at `origin` from the directions within `spread` radians of `dir` (unit), on
// average. A cone across the horizon (a refracted ray whose neighbours went up and down) takes
// the sky and the ground by the share of its elevations above and below (each seen along its
// part's middle elevation), not the one its axis points at.
vec3 environment_over(vec3 origin, vec3 dir, float spread) {
  float up = dot(dir, u_env_up);
  if (spread <= 0.0f) return up >= 0.0f ? sky_color(dir) : ground_over(origin, dir, 0.0f);
  float e = asin(clamp(up, -1.0f, 1.0f));
  if (e >= spread) return sky_color(dir);
  if (e <= -spread) return ground_over(origin, dir, spread);
  float above = 0.5f + 0.5f * e / spread;
  vec3 sky = sky_color(at_elevation(dir, 0.5f * (e + spread)));
  vec3 ground = ground_over(origin, at_elevation(dir, 0.5f * (e - spread)), spread);
  return mix(ground, sky, above);
}

// Radiance arriving at `origin` from direction `dir` (unit).
vec3 environment(vec3 origin, vec3 dir) { return environment_over(origin, dir, 0.0f); }

#endif
