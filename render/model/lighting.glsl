// render/model/lighting.glsl - the fluid's optics, shared by the shading modes ([ZD15], sec. 3.5,
// 3.6) on the GPU and on the C++ host (render/model/host.h: the CPU renderer and the reference):
// Fresnel reflectance (Schlick), Beer-Lambert transmittance with an RGB absorption coefficient, the
// light scattered out of the fluid towards the eye, and the opaque surface's lighting.
//
// Host needs: environment.glsl and its uniforms; u_absorption (per world unit, RGB), u_ior,
// u_scatter_color (radiance an infinitely deep body of fluid sends to the eye), u_albedo (opaque
// mode's surface colour).
#ifndef VX_MODEL_LIGHTING
#define VX_MODEL_LIGHTING

// Reflectance of the water-air interface for a ray meeting it at cos_theta on the less dense
// side (the cosine of the transmitted angle when the ray comes from inside).
float fresnel(float cos_theta) {
  float f0 = (u_ior - 1.0f) / (u_ior + 1.0f);
  f0 = f0 * f0;
  float m = 1.0f - clamp(cos_theta, 0.0f, 1.0f);
  return f0 + (1.0f - f0) * (m * m * m * m * m);
}

vec3 transmittance(float length_inside) { return exp(-u_absorption * length_inside); }

// Opaque mode: diffuse from sun and sky, ambient scaled by the occlusion, a small highlight.
vec3 opaque_surface(vec3 normal, vec3 view_dir, float occlusion) {
  float sun = max(dot(normal, u_sun_direction), 0.0f);
  float up = 0.5f + 0.5f * dot(normal, u_env_up);
  vec3 ambient = mix(0.5f * (u_ground_light + u_ground_dark), u_sky_zenith, up);
  vec3 half_vector = normalize(u_sun_direction - view_dir);
  float highlight = pow(max(dot(normal, half_vector), 0.0f), 64.0f);
  return u_albedo * (u_sun_color * sun + ambient * occlusion) + u_sun_color * (0.15f * highlight);
}

#endif
