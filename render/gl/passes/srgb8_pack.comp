// Linear RGBA to packed 8-bit sRGB (render/gl/passes/srgb8_pack.h): one thread per pixel, each
// channel as render/srgb8_image.cpp encodes it on the host.
layout(local_size_x = 64) in;

#include "render/gl/passes/thread_index.glsl"

layout(std430, binding = PICTURE_BINDING) readonly buffer Picture { vec4 picture[]; };
layout(std430, binding = TABLE_BINDING) readonly buffer Table { uint table[]; };
layout(std430, binding = PACKED_BINDING) writeonly buffer Srgb8 { uint srgb8_pixels[]; };

// linear_to_srgb8: the table's entry at linear * 2^TABLE_BITS + 0.5, rounded down. The product
// is exact (a power of two), so the sum's one rounding is the host's, fused or not.
uint srgb8(float linear) {
  if (isnan(linear) || linear <= 0.0) return 0u;
  if (linear >= 1.0) return 255u;
  uint i = uint(linear * float(1u << TABLE_BITS) + 0.5);
  return (table[i >> 2u] >> ((i & 3u) * 8u)) & 0xffu;
}

// linear_to_unorm8: alpha * 255 rounded half away from zero (std::lround), with no second
// rounding of an added 0.5.
uint unorm8(float alpha) {
  if (isnan(alpha) || alpha <= 0.0) return 0u;
  if (alpha >= 1.0) return 255u;
  float x = alpha * 255.0;
  uint r = uint(x);
  return x - float(r) >= 0.5 ? r + 1u : r;
}

void main() {
  uint p = thread_index();
  if (p >= u_thread_count) return;
  vec4 c = picture[p];
  srgb8_pixels[p] = srgb8(c.r) | (srgb8(c.g) << 8u) | (srgb8(c.b) << 16u) | (unorm8(c.a) << 24u);
}
