// render/gl/perspective_grid.glsl - the perspective grid of render/perspective_grid.h on the GPU:
// camera frame, pixel rays, logarithmic layers ([ZD15] sec. 4.2) and sphere footprints.
// Every pass that reads or writes voxels or spans includes it; set_grid_uniforms()
// (render/gl/uniforms.h) fills the uniforms. Depth = view z in world units; pixel row 0 is
// the top of the image.

uniform vec3 u_eye;
uniform vec3 u_right;
uniform vec3 u_up;
uniform vec3 u_forward;
uniform vec2 u_tan_half;       // image-plane half extents at depth 1 (x, y)
uniform ivec2 u_image;         // width, height in pixels
uniform float u_near;          // d_0
uniform float u_log2_step;     // log2(1 + K_d)
uniform float u_inv_log2_step; // 1 / log2(1 + K_d)
uniform uint u_layers;         // L, a multiple of 32
uniform float u_grid_far;      // d_L, the back of the last layer

vec3 to_view(vec3 world) {
  vec3 d = world - u_eye;
  return vec3(dot(d, u_right), dot(d, u_up), dot(d, u_forward));
}

// Ray through the pixel's centre with depth component 1 (view space).
vec3 view_ray(ivec2 pixel) {
  vec2 ndc = vec2(2.0 * (float(pixel.x) + 0.5) / float(u_image.x) - 1.0,
                  1.0 - 2.0 * (float(pixel.y) + 0.5) / float(u_image.y));
  return vec3(ndc * u_tan_half, 1.0);
}

vec3 world_ray(ivec2 pixel) {
  vec3 v = view_ray(pixel);
  return v.x * u_right + v.y * u_up + u_forward;
}

// World length per unit of depth along the pixel's ray.
float ray_scale(ivec2 pixel) { return length(view_ray(pixel)); }

// d_i = d_0 (1 + K_d)^i.
float layer_depth_at(float i) { return u_near * exp2(i * u_log2_step); }
float layer_depth(uint i) { return layer_depth_at(float(i)); }
float layer_of(float depth) { return log2(depth / u_near) * u_inv_log2_step; }
// Layer holding `depth`, clamped to [0, L - 1].
uint layer_index(float depth) {
  return uint(clamp(floor(layer_of(depth)), 0.0, float(u_layers - 1u)));
}

// Finite centre and radius > 0 (bit test: immune to fast-math folding of isnan).
bool valid_sphere(vec4 s) {
  uvec4 e = floatBitsToUint(s) & 0x7F800000u;
  return all(notEqual(e, uvec4(0x7F800000u))) && s.w > 0.0;
}

// Depth interval of the view-space ray z * d inside the sphere (c, r); false when it misses or
// only touches. Closest-approach form, as in the CPU reference, for precision with small,
// distant spheres.
bool sphere_chord(vec3 d, vec3 c, float r, out float z0, out float z1) {
  float a = dot(d, d);
  float zc = dot(d, c) / a;
  vec3 perp = c - zc * d;
  float h2 = r * r - dot(perp, perp);
  z0 = 0.0;
  z1 = 0.0;
  if (!(h2 > 0.0)) return false;
  float half_chord = sqrt(h2 / a);
  z0 = zc - half_chord;
  z1 = zc + half_chord;
  return true;
}

float pixel_coord(float slope, float tan_half, int size) {
  return (slope / tan_half + 1.0) * 0.5 * float(size) - 0.5;
}

// Pixel rectangle (x0, y0, x1, y1 inclusive) of a view-space sphere: the pixels whose centres
// lie within its silhouette's bounds (plus 0.01 pixel): every pixel whose centre ray meets it. Empty (x0 > x1) when outside the frustum's sides or
// behind the eye; the whole image when the sphere reaches the eye's plane. Same rule as
// PerspectiveGrid::sphere_pixels.
ivec4 sphere_pixels(vec3 c, float r) {
  const ivec4 none = ivec4(0, 0, -1, -1);
  if (c.z + r <= 0.0) return none;
  vec2 n = sqrt(1.0 + u_tan_half * u_tan_half);
  if ((abs(c.x) - u_tan_half.x * c.z) / n.x >= r) return none;
  if ((abs(c.y) - u_tan_half.y * c.z) / n.y >= r) return none;
  ivec2 last = u_image - 1;
  if (c.z - r <= 0.0) return ivec4(0, 0, last);
  // Exact silhouette slopes: tangents from the eye to the sphere's disk in the xz (yz) plane.
  vec2 t = c.xy / c.z;
  vec2 u = r / sqrt(c.xy * c.xy + c.z * c.z - r * r);
  vec2 s0 = (t - u) / (1.0 + t * u), s1 = (t + u) / (1.0 - t * u);
  float fx0 = pixel_coord(s0.x, u_tan_half.x, u_image.x);
  float fx1 = pixel_coord(s1.x, u_tan_half.x, u_image.x);
  float fy0 = pixel_coord(-s1.y, u_tan_half.y, u_image.y);
  float fy1 = pixel_coord(-s0.y, u_tan_half.y, u_image.y);
  const float margin = 0.01;  // past the silhouette, for float rounding (as on the CPU)
  if (fx1 < -margin || fx0 > float(last.x) + margin || fy1 < -margin || fy0 > float(last.y) + margin)
    return none;
  vec4 f = vec4(ceil(fx0 - margin), ceil(fy0 - margin), floor(fx1 + margin), floor(fy1 + margin));
  return ivec4(clamp(f, vec4(0.0), vec4(vec2(last), vec2(last))));
}
