// render/gl/passes/splat_common.glsl - marking one sphere's chord in one pixel's column, shared by
// the small-sphere splat (splat.comp) and the large-sphere splat (splat_large.comp), so both
// set exactly the same bits ([ZD15] sec. 4.1, 4.4). Needs render/gl/perspective_grid.glsl and
// render/gl/passes/bits.glsl; the pass defines BITS_BINDING.

layout(std430, binding = BITS_BINDING) buffer Bits { uint bits[]; };

uniform float u_gap;           // g (world units)
uniform uint u_surface_only;   // 1: entry and exit voxels only, where the gap allows

struct Chord {
  uint p;        // tile pixel
  uint l0, l1;   // first and last layer the chord touches
  bool surface;  // mark l0 and l1 only
};

// The chord of the pixel's centre ray through the sphere (view space), as layers.
bool pixel_chord(vec4 sphere, ivec2 pixel, out Chord c) {
  c = Chord(0u, 0u, 0u, false);
  float z0, z1;
  vec3 ray = view_ray(pixel);
  if (!sphere_chord(ray, sphere.xyz, sphere.w, z0, z1)) return false;
  if (z1 <= u_near || z0 >= u_grid_far) return false;
  c.l0 = layer_index(max(z0, u_near));
  c.l1 = layer_index(z1);
  c.p = uint(pixel.x - u_tile.x) + uint(pixel.y - u_tile.y) * uint(u_tile.z);
  if (u_surface_only != 0u) {
    // Compress measures a gap between voxel centres: at most the chord plus one layer (a layer
    // at depth z is at most K_d z thick). The margin keeps float rounding from opening a gap
    // that would not close.
    float widest_gap = 2.0 * sphere.w + (exp2(u_log2_step) - 1.0) * z1 * length(ray);
    c.surface = 1.001 * widest_gap < u_gap;
  }
  return true;
}

void set_layer(uint p, uint l) { atomicOr(bits[bit_word_index(p, l >> 5u)], 1u << (l & 31u)); }

// Sets layers l0..l1 of column p, but only in words wa..wb: whole words at once.
void set_layers_in_words(uint p, uint l0, uint l1, uint wa, uint wb) {
  uint w0 = l0 >> 5u, w1 = l1 >> 5u;
  for (uint w = max(w0, wa); w <= min(w1, wb); ++w) {
    uint lo = w == w0 ? (l0 & 31u) : 0u;
    uint hi = w == w1 ? (l1 & 31u) : 31u;
    atomicOr(bits[bit_word_index(p, w)], bit_range_mask(lo, hi));
  }
}

void splat_pixel(vec4 sphere, ivec2 pixel) {
  Chord c;
  if (!pixel_chord(sphere, pixel, c)) return;
  if (c.surface) {
    set_layer(c.p, c.l0);
    set_layer(c.p, c.l1);
  } else {
    set_layers_in_words(c.p, c.l0, c.l1, 0u, 0xFFFFFFFFu);
  }
}
