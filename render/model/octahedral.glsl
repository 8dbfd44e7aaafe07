// render/model/octahedral.glsl - unit normals in one 32-bit word: octahedral mapping to the square
// [-1, 1]^2, two 16-bit signed normalized integers ([ZD15] sec. 4.5, after Meyer et al. 2010).
// Worst round-trip error about 0.003 degrees. Shared by the GPU passes and the C++ host
// (render/model/host.h: the CPU renderer and the reference).
#ifndef VX_MODEL_OCTAHEDRAL
#define VX_MODEL_OCTAHEDRAL

vec2 octahedral_sign(vec2 v) { return vec2(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f); }

uint encode_normal(vec3 n) {
  vec3 a = abs(n);
  float l1 = a.x + a.y + a.z;
  if (!(l1 > 0.0f)) return packSnorm2x16(vec2(0.0f));  // decodes to +z
  vec2 e = vec2(n.x, n.y) / l1;
  if (n.z < 0.0f) e = (vec2(1.0f) - abs(vec2(e.y, e.x))) * octahedral_sign(e);
  return packSnorm2x16(e);
}

vec3 decode_normal(uint word) {
  vec2 e = unpackSnorm2x16(word);
  vec3 v = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
  if (v.z < 0.0f) {
    vec2 xy = (vec2(1.0f) - abs(vec2(e.y, e.x))) * octahedral_sign(e);
    v.x = xy.x;
    v.y = xy.y;
  }
  return normalize(v);
}

#endif
