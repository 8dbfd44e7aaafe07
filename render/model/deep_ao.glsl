// render/model/deep_ao.glsl - deep ambient occlusion ([ZD15] sec. 3.6): the occlusion of a pixel's
// front surface, sampled from the surface points of neighbouring columns within a world radius,
// over ALL their stored spans, not only the front ones (after Mittring 2007's screen-space AO).
// Shared by the GPU pass (render/gl/passes/deep_ao.comp) and the C++ host (render/model/host.h: the
// CPU renderer and the reference).
//
// u_ao_samples columns on a golden-angle spiral over the disk that the radius covers on screen
// (rotated per pixel); in each, the spans reaching within the radius in depth (at most
// VX_AO_SPANS of them), each clipped to the receiver's depth +- radius. A clipped span occludes by
// the elevation of its nearer end above the receiver's tangent plane (less a small bias against
// self-occlusion on flat surfaces), weighted down with distance; a column counts its most
// occluding span. ao = 1 - strength * mean occlusion, in [0, 1].
//
// Host needs: links.glsl, surface_geometry.glsl, octahedral.glsl and their needs;
// uvec2 sd_normals(uint), u_ao_radius (world units), u_ao_strength, u_ao_samples (<= 64).
#ifndef VX_MODEL_DEEP_AO
#define VX_MODEL_DEEP_AO

#define VX_AO_SPANS 4u
#define VX_AO_BIAS 0.1f

float point_occlusion(vec3 receiver, vec3 normal, vec3 occluder) {
  vec3 v = occluder - receiver;
  float dist = length(v);
  if (!(dist > 1e-6f * receiver.z) || dist > u_ao_radius) return 0.0f;
  float r = dist / u_ao_radius;
  return max(dot(normal, v) / dist - VX_AO_BIAS, 0.0f) * (1.0f - r * r);
}

float column_occlusion(ivec2 q, vec3 receiver, vec3 normal) {
  vec3 ray = view_ray_at(vec2(q) + vec2(0.5f));
  float lo = receiver.z - u_ao_radius;
  float hi = receiver.z + u_ao_radius;
  uint count = sd_count(q);
  uint base = sd_offset(q);
  uint first = first_span_exiting_after(q, lo);
  float most = 0.0f;
  for (uint k = first; k < count && k < first + VX_AO_SPANS; ++k) {
    vec2 span = sd_raw_depths(base + k);
    if (span.x > hi) break;
    float front = max(span.x, lo);
    float back = min(span.y, hi);
    most = max(most, point_occlusion(receiver, normal, ray * front));
    most = max(most, point_occlusion(receiver, normal, ray * back));
  }
  return most;
}

float deep_ao(ivec2 p) {
  if (sd_count(p) == 0u) return 1.0f;
  uint base = sd_offset(p);
  vec3 receiver = point_position(surface_point(p, base, 0u));
  vec3 normal = world_to_view_direction(decode_normal(sd_normals(base).x));
  float pixel_size = 2.0f * u_tan_half.y / float(u_image.y) * receiver.z;
  float radius_px = u_ao_radius / pixel_size;
  // Per-pixel rotation of the spiral (R2 low-discrepancy sequence).
  float turn = 6.2831853f * fract(0.7548777f * float(p.x) + 0.5698403f * float(p.y));
  float occlusion = 0.0f;
  for (int i = 0; i < u_ao_samples; ++i) {
    float r = sqrt((float(i) + 0.5f) / float(u_ao_samples)) * radius_px;
    float a = turn + 2.3999632f * float(i);
    ivec2 q = p + ivec2(int(floor(r * cos(a) + 0.5f)), int(floor(r * sin(a) + 0.5f)));
    if ((q.x == p.x && q.y == p.y) || !in_image(q)) continue;
    occlusion += column_occlusion(q, receiver, normal);
  }
  return clamp(1.0f - u_ao_strength * occlusion / float(max(u_ao_samples, 1)), 0.0f, 1.0f);
}

#endif
