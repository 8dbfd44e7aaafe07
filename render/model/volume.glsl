// render/model/volume.glsl - the compositing of a volume view's samples along one ray ([FAW10]
// sec. 5, [HOK16] Eq. 3), shared by every volume renderer and the reference (render/volume.h
// says what the samples are): front to back, iso crossings between neighbouring samples first
// (nearest first; the host lights them once it has the field's gradient there), then the
// volume's emission and absorption through the transfer function, its opacity corrected to the
// sample's length. The host stops the ray when its transmittance falls under the termination.
//
// Host needs: VX_TRANSFER_ENTRIES, VX_MAX_ISO; vec4 vx_transfer_entry(int) (the table: linear
// RGB and opacity); u_tf_log (1: the table spans log2 q), u_tf_lo and u_tf_scale
// ((entries - 1) / (hi - lo), of log2 q where u_tf_log); u_opacity_length;
// u_mode (VX_VOLUME_*); u_iso_count, u_iso_value[], u_iso_opacity[], u_iso_color[];
// u_ambient, u_light (unit, towards the light); void vx_record_hit(float depth, float weight,
// uint iso) (an iso crossing at `depth` whose lit colour adds `weight` times over).
#ifndef VX_MODEL_VOLUME
#define VX_MODEL_VOLUME

#define VX_VOLUME_DVR 0u
#define VX_VOLUME_ISO 1u
#define VX_VOLUME_MIXED 2u

struct VolumeRay {
  vec3 color;           // the volume's light composited so far (premultiplied)
  float transmittance;  // of everything composited so far
  float q;              // the previous sample's value
  float depth;          // its depth
  uint defined;         // 1: the previous sample had a value (some particle reached it)
};

VolumeRay vx_ray_start() {
  VolumeRay r;
  r.color = vec3(0.0f);
  r.transmittance = 1.0f;
  r.q = 0.0f;
  r.depth = 0.0f;
  r.defined = 0u;
  return r;
}

// The transfer function at q: the table interpolated linearly, clamped at its ends (on a log
// scale a value at or under 0 below its first entry).
vec4 vx_transfer(float q) {
  float v = q;
  if (u_tf_log != 0u) v = q > 0.0f ? log2(q) : u_tf_lo - 1.0f;
  float x = clamp((v - u_tf_lo) * u_tf_scale, 0.0f, float(VX_TRANSFER_ENTRIES - 1));
  int k = min(int(x), VX_TRANSFER_ENTRIES - 2);
  return mix(vx_transfer_entry(k), vx_transfer_entry(k + 1), x - float(k));
}

// The opacity of `length` world units of a medium whose opacity over u_opacity_length is alpha.
float vx_length_opacity(float alpha, float length) {
  if (alpha >= 1.0f) return 1.0f;
  if (alpha <= 0.0f) return 0.0f;
  return 1.0f - exp2(log2(1.0f - alpha) * (length / u_opacity_length));
}

// Where iso surface k crosses between the previous sample and (q, depth): the depth, linear in
// the values; -1 when it does not.
float vx_iso_crossing(VolumeRay r, float q, float depth, uint k) {
  float iso = u_iso_value[k];
  float a = r.q - iso;
  float b = q - iso;
  if (!((a < 0.0f && b >= 0.0f) || (a >= 0.0f && b < 0.0f))) return -1.0f;
  return r.depth + (depth - r.depth) * (a / (a - b));
}

// The iso crossings between the previous sample and (q, depth), where both are defined: each
// recorded (nearest first) and its opacity taken from the transmittance.
VolumeRay vx_iso_crossings(VolumeRay r, float q, uint defined, float depth) {
  if (u_mode == VX_VOLUME_DVR || defined != 1u || r.defined != 1u) return r;
  float t[VX_MAX_ISO];
  uint which[VX_MAX_ISO];
  uint n = 0u;
  for (uint k = 0u; k < u_iso_count; ++k) {
    float c = vx_iso_crossing(r, q, depth, k);
    if (c < 0.0f) continue;
    uint j = n;  // insertion, nearest first
    while (j > 0u && t[j - 1u] > c) {
      t[j] = t[j - 1u];
      which[j] = which[j - 1u];
      --j;
    }
    t[j] = c;
    which[j] = k;
    ++n;
  }
  for (uint j = 0u; j < n; ++j) {
    float a = u_iso_opacity[which[j]];
    vx_record_hit(t[j], r.transmittance * a, which[j]);
    r.transmittance *= 1.0f - a;
  }
  return r;
}

// One sample at `depth`, standing for `length` world units of the ray, of value q where
// defined == 1u: the crossings before it, then its own light and absorption.
VolumeRay vx_sample(VolumeRay r, float q, uint defined, float depth, float length) {
  r = vx_iso_crossings(r, q, defined, depth);
  if (u_mode != VX_VOLUME_ISO && defined == 1u) {
    vec4 c = vx_transfer(q);
    float a = vx_length_opacity(c.a, length);
    r.color += (r.transmittance * a) * vec3(c.r, c.g, c.b);
    r.transmittance *= 1.0f - a;
  }
  r.q = q;
  r.depth = depth;
  r.defined = defined;
  return r;
}

// Iso surface k's colour at a point of unit normal `normal` (either side) seen along `to_eye`
// (unit): Lambert and a Blinn-Phong highlight from u_light, u_ambient from everywhere.
vec3 vx_iso_light(uint k, vec3 normal, vec3 to_eye) {
  vec3 n = dot(normal, to_eye) < 0.0f ? -normal : normal;
  float diffuse = max(dot(n, u_light), 0.0f);
  vec3 h = normalize(u_light + to_eye);
  float specular = 0.25f * pow(max(dot(n, h), 0.0f), 32.0f);
  return u_iso_color[k] * (u_ambient + (1.0f - u_ambient) * diffuse) + vec3(specular);
}

#endif
