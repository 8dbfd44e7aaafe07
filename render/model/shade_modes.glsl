// render/model/shade_modes.glsl - the opaque and translucent shading of one pixel ([ZD15], sec.
// 3.5), shared by the GPU passes (render/gl/passes/shade_opaque.comp, shade_translucent.comp) and
// the C++ host (render/model/host.h: the CPU renderer and the reference).
//
// Translucent: Fresnel reflection of the environment at the first entry; the rest passes
// straight through every span, absorbed (Beer-Lambert) over each span's length and lit by the
// light the fluid scatters towards the eye. The last span's length is `inside` minus the
// others, so a capped pixel (whose last stored span was extended over the spans past the cap,
// sec. 3.1) absorbs exactly as much as if every span were stored.
//
// Host needs: links.glsl, surface_geometry.glsl, octahedral.glsl, lighting.glsl and their
// needs; float sd_inside(ivec2), uvec2 sd_normals(uint) (entry, exit words), float sd_ao(ivec2)
// (used when u_use_ao != 0), vec3 sd_background(ivec2 p, vec3 dir) (environment(u_eye, dir) for
// dir = pixel_direction(p): what lies behind the pixel, which a host may keep while the camera
// stays), u_eye.
#ifndef VX_MODEL_SHADE_MODES
#define VX_MODEL_SHADE_MODES

vec3 pixel_direction(ivec2 p) { return normalize(view_to_world_direction(view_ray_at(vec2(p) + vec2(0.5f)))); }

float pixel_occlusion(ivec2 p) { return u_use_ao != 0 ? sd_ao(p) : 1.0f; }

// The reflection of pixel p's front surface (view direction `dir`, normal `normal`) over its
// footprint, sampled by the pixels its first entry links to (the same surface): where the surface
// curves fast, a crest's rim, neighbouring pixels reflect directions far apart and at far
// different Fresnel factors, and one ray a pixel samples both more sparsely than a pixel. x: half
// the largest angle between the reflected directions, over which the environment is averaged
// (environment_over, as wall_light for refracted rays); y: the mean Fresnel reflectance.
vec2 reflection_footprint(ivec2 p, vec3 dir, vec3 normal) {
  vec3 r = reflect(dir, normal);
  SurfacePoint v = surface_point(p, sd_offset(p), 0u);
  float spread = 0.0f;
  float reflectance = fresnel(-dot(dir, normal));
  float samples = 1.0f;
  for (int k = 0; k < 4; ++k) {
    if (!link_is_across(v, k)) continue;
    SurfacePoint w = follow_link(v, k);
    vec3 n = decode_normal(sd_normals(w.span).x);
    vec3 dw = pixel_direction(w.pixel);
    spread = max(spread, 0.5f * acos(clamp(dot(r, reflect(dw, n)), -1.0f, 1.0f)));
    reflectance += fresnel(-dot(dw, n));
    samples += 1.0f;
  }
  return vec2(spread, reflectance / samples);
}

vec3 shade_opaque(ivec2 p) {
  vec3 dir = pixel_direction(p);
  if (sd_count(p) == 0u) return sd_background(p, dir);
  vec3 normal = decode_normal(sd_normals(sd_offset(p)).x);
  return opaque_surface(normal, dir, pixel_occlusion(p));
}

vec3 shade_translucent(ivec2 p) {
  vec3 dir = pixel_direction(p);
  vec3 behind = sd_background(p, dir);
  uint n = sd_count(p);
  if (n == 0u) return behind;
  uint base = sd_offset(p);
  vec3 ray = view_to_world_direction(view_ray_at(vec2(p) + vec2(0.5f)));
  vec3 entry = u_eye + ray * sd_depths(base).x;
  vec3 normal = decode_normal(sd_normals(base).x);
  vec2 footprint = reflection_footprint(p, dir, normal);
  float reflectance = footprint.y;
  vec3 reflected = environment_over(entry, reflect(dir, normal), footprint.x);

  float scale = length(ray);
  float inside = sd_inside(p);
  float counted = 0.0f;
  vec3 through = vec3(1.0f);
  vec3 scattered = vec3(0.0f);
  for (uint k = 0u; k < n; ++k) {
    vec2 span = sd_raw_depths(base + k);
    float len = k + 1u < n ? (span.y - span.x) * scale : max(inside - counted, 0.0f);
    counted += len;
    vec3 t = transmittance(len);
    scattered += through * (vec3(1.0f) - t);
    through *= t;
  }
  vec3 body = through * behind + scattered * u_scatter_color * pixel_occlusion(p);
  return reflectance * reflected + (1.0f - reflectance) * body;
}

#endif
