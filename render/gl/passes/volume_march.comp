// The volume march (render/gl/passes/volume_march.h): a work group per bundle of 8x8 pixels, a
// thread per pixel. The bundle's supports (those of its 32-pixel tile, nearest first sample
// first) go through shared memory 64 at a time; each thread adds their kernels at its ray's
// samples of one slab of VM_SLAB samples into its own sums, in the list's order (no atomics:
// the sums do not depend on the threads' order), then composites the slab through the shared
// model (render/model/volume.glsl); the bundle stops when every ray is opaque. Then the iso hits'
// gradients from the same supports, their light, and the background.
// With adaptive sampling the bundle follows its cells' plans as the CPU caster's march does
// (render/cpu/volume_adaptive.h): in a cell at level l the supports add their kernels at the
// first sample of each 2^l only, which stands for the run's length; a super-pixel cell is
// summed nowhere and every ray takes the cell's one light and transmittance.
layout(local_size_x = 64) in;

#include "render/gl/passes/shade_uniforms.glsl"

// std430: scalars, not a dvec4 (aligned to 32 bytes, it would pad the struct to 96).
struct Support {
  double cx, cy, cz, radius;  // view-space centre, support radius
  vec4 weights;               // 1 / h, V, V q, unused
  ivec4 samples_rect;         // first and last sample (from u_base), x0, y0
  ivec4 rect_end;             // x1, y1, unused, unused
};
layout(std430, binding = VM_SUPPORTS) readonly buffer Supports { Support supports[]; };
layout(std430, binding = VM_TILE_START) readonly buffer TileStart { uint tile_start[]; };
layout(std430, binding = VM_TILE_LISTS) readonly buffer TileLists { uint tile_lists[]; };
layout(std430, binding = VM_DEPTHS) readonly buffer Depths { double depths[]; };
layout(std430, binding = VM_TRANSFER) readonly buffer Transfer { vec4 transfer[]; };
layout(std430, binding = VM_PICTURE) writeonly buffer Picture { vec4 picture[]; };
layout(std430, binding = VM_DEPTH) writeonly buffer FirstDepth { float first_depth[]; };
// With u_walls: per pixel the colour behind the fluid and, in alpha, the first sample behind its
// walls (-1: no wall).
layout(std430, binding = VM_WALLS) readonly buffer Walls { vec4 walls[]; };
// samples, kernel evaluations (low, high words), rays stopped, iso hits, unlit hits, bundles
// past the budget, samples skipped
layout(std430, binding = VM_COUNTS) buffer Counts { uint counts[]; };
// Adaptive sampling's plans (GpuPlans, render/cpu/volume_caster.h): per bundle its first cell's
// word or VM_FULL_RATE; per cell its level in the low VM_LEVEL_BITS and a super-pixel's index
// above them; per super-pixel its light (premultiplied) and transmittance.
layout(std430, binding = VM_BUNDLE_CELLS) readonly buffer BundleCells { uint bundle_cells[]; };
layout(std430, binding = VM_CELLS) readonly buffer Cells { uint cells[]; };
layout(std430, binding = VM_SUPER_PIXELS) readonly buffer SuperPixels { vec4 super_pixels[]; };

uniform ivec2 u_image;
uniform int u_tiles_x;
uniform int u_samples;  // depths' length
uniform dvec2 u_tan_half;
uniform vec3 u_eye;
uniform vec3 u_right;
uniform vec3 u_up;
uniform vec3 u_forward;
uniform double u_near;
uniform uint u_kernel;  // VM_KERNEL_*
uniform int u_shepard;
uniform float u_weight_floor;
uniform float u_termination;
uniform double u_half_extent;  // VolumeLattice::half_extent
uniform double u_lattice_k;
uniform int u_background;
uniform int u_walls;
uniform int u_adaptive;  // 1: the plans above apply
// The first sample's lattice index mod 2^VM_CELL_SHIFT: (i + u_phase) >> VM_CELL_SHIFT numbers
// sample i's cell, and a run of 2^l starts where i + u_phase is a multiple of 2^l.
uniform int u_phase;
// Per level l the depths of a run of 2^l samples over its first's.
uniform double u_run_length[VM_CELL_SHIFT + 1];
// Loop iterations a thread may spend, 0: no bound. llvmpipe stops an invocation silently after
// 65535 (all its loops together, GPU-NOTES). It runs 8 threads in step under masks: a loop lasts
// as long as its longest lane, and costs one more pass (its exit test) even where no lane enters
// it. So `spent` counts each loop's bound for the whole bundle, plus one per entry, not this
// thread's trips. Past the budget the bundle stops and says so in counts[6], and the renderer
// draws the frame on the CPU.
uniform uint u_budget;
// render/model/volume.glsl's
uniform uint u_tf_log;
uniform float u_tf_lo;
uniform float u_tf_scale;
uniform float u_opacity_length;
uniform uint u_mode;
uniform uint u_iso_count;
uniform float u_iso_value[VX_MAX_ISO];
uniform float u_iso_opacity[VX_MAX_ISO];
uniform vec3 u_iso_color[VX_MAX_ISO];
uniform float u_ambient;
uniform vec3 u_light;

#define VX_MAX_HITS 8
float hit_depth[VX_MAX_HITS];
float hit_weight[VX_MAX_HITS];
uint hit_iso[VX_MAX_HITS];
int hit_count = 0;
vec3 unlit = vec3(0.0);
uint unlit_count = 0u;

vec4 vx_transfer_entry(int k) { return transfer[k]; }
void vx_record_hit(float depth, float weight, uint iso) {
  if (hit_count < VX_MAX_HITS) {
    hit_depth[hit_count] = depth;
    hit_weight[hit_count] = weight;
    hit_iso[hit_count] = iso;
    ++hit_count;
  } else {
    unlit += weight * u_ambient * u_iso_color[iso];
    ++unlit_count;
  }
}

#include "render/model/environment.glsl"
#include "render/model/volume.glsl"
#include "render/gl/passes/volume_kernel.glsl"

shared dvec4 sh_centre_radius[64];
shared vec4 sh_weights[64];
shared ivec4 sh_samples_rect[64];
shared ivec2 sh_rect_end[64];
shared uint sh_done;
shared int sh_last;
shared uint sh_counts[6];
shared uint sh_overflow;
shared int sh_max_hits;
uint spent = 0u;  // the bundle's loop iterations, at most (the same in every thread)

// The supports of entries [first, first + 64) of the list into shared memory, or false when
// the bundle has spent its budget. A thread over it says so before the first barrier and every
// thread reads the flag before the second: llvmpipe runs the bundle's threads 8 at a time, up
// to each barrier in turn, so a read after the second could see the next chunk's flag.
bool load_chunk(uint first, uint end) {
  if (u_budget > 0u && spent > u_budget) atomicOr(sh_overflow, 1u);
  barrier();
  bool overflow = sh_overflow != 0u;
  uint k = first + gl_LocalInvocationIndex;
  if (k < end) {
    Support s = supports[tile_lists[k]];
    sh_centre_radius[gl_LocalInvocationIndex] = dvec4(s.cx, s.cy, s.cz, s.radius);
    sh_weights[gl_LocalInvocationIndex] = s.weights;
    sh_samples_rect[gl_LocalInvocationIndex] = s.samples_rect;
    sh_rect_end[gl_LocalInvocationIndex] = s.rect_end.xy;
  }
  barrier();
  return !overflow;
}

// The first sample in [lo, hi) whose depth is at or after d (hi when none): a binary search.
int vm_first_at_or_after(int lo, int hi, double d) {
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (depths[mid] < d) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

// Adaptive sampling: the bundle's first cell's word in `cells` (VM_FULL_RATE: none), and the
// cell of its tile's first sample.
uint plan_first = uint(VM_FULL_RATE);
int cell_first = 0;

const uint kLevelMask = (1u << VM_LEVEL_BITS) - 1u;

uint cell_word(int i) {
  return cells[plan_first + uint(((i + u_phase) >> VM_CELL_SHIFT) - cell_first)];
}
// Sample i's cell's level (CellPlan::level; 0 where the bundle has no plan).
uint level_at(int i) { return plan_first == uint(VM_FULL_RATE) ? 0u : cell_word(i) & kLevelMask; }

// Bits a..b of a word (none where a > b); 0 <= a, b <= 31 where a <= b.
uint bits_between(int a, int b) {
  return a > b ? 0u : (0xffffffffu >> uint(31 - b)) & (0xffffffffu << uint(a));
}

// The samples of [s0, s1] (fewer than 33) the bundle's plans take, bit i - s0 for sample i: all
// at full rate, the first of each 2^l in a cell at level l, none in a super-pixel.
uint taken_samples(int s0, int s1) {
  if (plan_first == uint(VM_FULL_RATE)) return 0xffffffffu;
  uint taken = 0u;
  for (int c = (s0 + u_phase) >> VM_CELL_SHIFT; c <= (s1 + u_phase) >> VM_CELL_SHIFT; ++c) {
    uint level = cells[plan_first + uint(c - cell_first)] & kLevelMask;
    // Of the cell's 16 samples, bits 0, 2^l, 2 2^l, ...: 0xffff / (2^(2^l) - 1).
    uint runs = level == VM_SUPER_PIXEL ? 0u : 0xffffu / ((1u << (1u << level)) - 1u);
    int at = (c << VM_CELL_SHIFT) - u_phase - s0;
    taken |= at >= 0 ? runs << uint(at) : runs >> uint(-at);
  }
  return taken;
}

bool covers(int j, ivec2 pixel) {
  ivec4 a = sh_samples_rect[j];
  ivec2 b = sh_rect_end[j];
  return pixel.x >= a.z && pixel.y >= a.w && pixel.x <= b.x && pixel.y <= b.y;
}

void main() {
  ivec2 bundle = ivec2(gl_WorkGroupID.xy);
  ivec2 pixel =
      bundle * 8 + ivec2(int(gl_LocalInvocationIndex % 8u), int(gl_LocalInvocationIndex / 8u));
  bool inside = pixel.x < u_image.x && pixel.y < u_image.y;
  // Every thread of a bundle shares its 32-pixel tile (8 divides 32).
  uint tile = uint(bundle.x / 4) + uint(bundle.y / 4) * uint(u_tiles_x);
  uint list_begin = tile_start[tile], list_end = tile_start[tile + 1u];

  dvec3 dir =
      dvec3((2.0lf * (double(pixel.x) + 0.5lf) / double(u_image.x) - 1.0lf) * u_tan_half.x,
            (1.0lf - 2.0lf * (double(pixel.y) + 0.5lf) / double(u_image.y)) * u_tan_half.y, 1.0lf);
  double a = dot(dir, dir), inv_a = 1.0lf / a;
  float scale = float(sqrt(a));

  if (gl_LocalInvocationIndex == 0u) {
    sh_done = 0u;
    sh_overflow = 0u;
    sh_last = -1;
    sh_max_hits = 0;
    for (int c = 0; c < 6; ++c) sh_counts[c] = 0u;
  }
  barrier();
  // The bundle's last sample: the largest `last` of its supports.
  for (uint k = list_begin + gl_LocalInvocationIndex; k < list_end; k += 64u, ++spent)
    atomicMax(sh_last, supports[tile_lists[k]].samples_rect.y);
  barrier();
  int last = sh_last;
  int first = list_begin < list_end ? supports[tile_lists[list_begin]].samples_rect.x : 0;
  if (u_adaptive != 0) {
    plan_first = bundle_cells[gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x];
    cell_first = (first + u_phase) >> VM_CELL_SHIFT;
  }
  int super_cell = -1;  // the last super-pixel cell the ray took

  uint p = uint(pixel.x) + uint(pixel.y) * uint(u_image.x);
  vec4 wall = u_walls != 0 && inside ? walls[p] : vec4(0.0, 0.0, 0.0, -1.0);
  int wall_end = wall.a >= 0.0 ? int(wall.a) : 0x7fffffff;
  VolumeRay ray = vx_ray_start();
  float first_hit = 0.0;
  bool first_is_hit = false;
  bool done = !inside;
  uint my_samples = 0u, my_evaluations = 0u, my_skipped = 0u;
  float sums[VM_SLAB];
  float weights[VM_SLAB];
  // The list's supports before `start` end before the current slab (sorted by first sample, so
  // the prefix of those ending early only grows).
  uint start = list_begin;
  bool overflow = false;  // the same in every thread
  // A sample's compositing loops (render/model/volume.glsl): the surfaces' tests, each with its
  // insertion, and the records.
  uint isos = u_mode == VX_VOLUME_DVR ? 0u : u_iso_count;
  uint per_sample = 1u + (isos + 1u) * (isos + 2u) + (isos + 1u);
  for (int s0 = first; s0 <= last; s0 += VM_SLAB) {
    for (int i = 0; i < VM_SLAB; ++i) sums[i] = weights[i] = 0.0;
    int s1 = min(s0 + VM_SLAB - 1, last);
    // The slab's setup, its plans' cells (at most 3) and its compositing.
    spent += uint(VM_SLAB + 9) + uint(s1 - s0 + 1) * per_sample;
    uint taken = taken_samples(s0, s1);
    for (; start < list_end && supports[tile_lists[start]].samples_rect.y < s0; ++start) ++spent;
    for (uint chunk = start; chunk < list_end; chunk += 64u) {
      if (supports[tile_lists[chunk]].samples_rect.x > s1) break;  // sorted: none further
      spent += 2u;
      if (!load_chunk(chunk, list_end)) {
        overflow = true;
        break;
      }
      int n = int(min(64u, list_end - chunk));
      for (int j = 0; j < n; ++j) {
        ivec4 sr = sh_samples_rect[j];
        if (sr.x > s1) break;
        // This pass, and at most the support's samples in the slab and their binary search.
        int span = min(sr.y, s1) - max(sr.x, s0) + 1;
        spent += 3u + (span > 0 ? uint(span) + uint(findMSB(span)) + 1u : 0u);
        if (sr.y < s0 || done || !covers(j, pixel)) continue;
        int hi = min(sr.y, s1);
        if ((taken & bits_between(max(sr.x, s0) - s0, hi - s0)) == 0u) continue;  // none taken
        dvec3 c = sh_centre_radius[j].xyz;
        double radius = sh_centre_radius[j].w;
        double zc = (dir.x * c.x + dir.y * c.y + c.z) * inv_a;
        dvec3 m = zc * dir - c;
        double m2 = dot(m, m);
        double h2 = (radius * radius - m2) * inv_a;
        if (!(h2 > 0.0lf)) continue;
        double half_chord = sqrt(h2);
        double d0 = max(zc - half_chord, u_near), d1 = zc + half_chord;
        vec4 w = sh_weights[j];
        int lo = vm_first_at_or_after(max(sr.x, s0), hi + 1, d0);
        for (uint bits = taken & bits_between(lo - s0, hi - s0); bits != 0u; bits &= bits - 1u) {
          int i = s0 + findLSB(bits);
          double z = depths[i];
          if (z > d1) break;
          double t = z - zc;
          float shape = vm_kernel_shape(float(sqrt(a * t * t + m2)) * w.x);
          sums[i - s0] += w.z * shape;
          weights[i - s0] += w.y * shape;
          ++my_evaluations;
        }
      }
    }
    for (int i = s0; i <= s1 && !done; ++i) {
      if (i >= wall_end) {  // the ray ends at its walls
        done = true;
        break;
      }
      uint level = level_at(i);
      if ((taken & (1u << uint(i - s0))) == 0u) {  // a run's first stood for it, or a super-pixel
        ++my_skipped;
        int cell = (i + u_phase) >> VM_CELL_SHIFT;
        if (level != VM_SUPER_PIXEL || cell == super_cell) continue;
        // The cell's light and transmittance, once, as render/cpu/volume_caster.cpp's.
        super_cell = cell;
        vec4 sp = super_pixels[cell_word(i) >> VM_LEVEL_BITS];
        float before = ray.transmittance;
        ray.color += before * sp.rgb;
        ray.transmittance *= sp.a;
        ray.defined = 1u;
        int middle = (cell << VM_CELL_SHIFT) - u_phase + (1 << VM_CELL_SHIFT) / 2;
        if (first_hit == 0.0 && before >= 0.5 && ray.transmittance < 0.5)
          first_hit = float(depths[middle]) * scale;
        if (ray.transmittance < u_termination) {
          done = true;
          atomicAdd(sh_counts[2], 1u);
        }
        continue;
      }
      float sw = weights[i - s0];
      bool defined = sw > 0.0 && (u_shepard == 0 || sw >= u_weight_floor);
      float q = !defined ? 0.0 : (u_shepard != 0 ? sums[i - s0] / sw : sums[i - s0]);
      my_samples += defined ? 1u : 0u;
      double z = depths[i];
      float len = float(z * u_half_extent * u_run_length[level]) * scale;
      float before = ray.transmittance;
      int hits = hit_count;
      ray = vx_sample(ray, q, defined ? 1u : 0u, float(z), len);
      if (first_hit == 0.0 && hit_count > hits) {
        first_hit = hit_depth[0] * scale;
        first_is_hit = true;
      }
      if (first_hit == 0.0 && before >= 0.5 && ray.transmittance < 0.5)
        first_hit = float(z) * scale;
      if (ray.transmittance < u_termination) {
        done = true;
        atomicAdd(sh_counts[2], 1u);
      }
    }
    barrier();
    if (done) atomicAdd(sh_done, 1u);
    barrier();
    bool all_done = sh_done == 64u || overflow;
    barrier();
    if (gl_LocalInvocationIndex == 0u) sh_done = 0u;
    if (all_done) break;
  }

  // The hits' field sums and gradients from the tile's supports, in double (the Shepard
  // quotient's gradient cancels), then their light.
  dvec2 hit_sums[VX_MAX_HITS];  // s, w
  dvec3 grad_s[VX_MAX_HITS];
  dvec3 grad_w[VX_MAX_HITS];
  for (int h = 0; h < VX_MAX_HITS; ++h) {
    hit_sums[h] = dvec2(0.0lf);
    grad_s[h] = dvec3(0.0lf);
    grad_w[h] = dvec3(0.0lf);
  }
  atomicMax(sh_max_hits, hit_count);
  barrier();
  int max_hits = sh_max_hits;
  for (uint chunk = list_begin; chunk < list_end && max_hits > 0; chunk += 64u) {
    spent += 2u;
    if (!load_chunk(chunk, list_end)) break;
    int n = int(min(64u, list_end - chunk));
    for (int j = 0; j < n; ++j) {
      spent += 2u + uint(max_hits);
      if (!covers(j, pixel)) continue;
      dvec3 c = sh_centre_radius[j].xyz;
      vec4 w = sh_weights[j];
      for (int h = 0; h < hit_count; ++h) {
        dvec3 d = double(hit_depth[h]) * dir - c;
        double dist = length(d);
        double q = dist * double(w.x);
        double shape = vm_kernel_shape_d(q);
        if (shape == 0.0lf && q >= double(vm_kernel_support())) continue;
        dvec3 g = dist > 0.0lf ? (vm_kernel_slope_d(q) * double(w.x) / dist) * d : dvec3(0.0lf);
        hit_sums[h] += dvec2(double(w.z), double(w.y)) * shape;
        grad_s[h] += double(w.z) * g;
        grad_w[h] += double(w.y) * g;
      }
    }
  }
  vec3 world_dir = normalize(float(dir.x) * u_right + float(dir.y) * u_up + u_forward);
  for (int h = 0; h < hit_count; ++h) {
    double fs = hit_sums[h].x, fw = hit_sums[h].y;
    bool shepard = u_shepard != 0 && fw > 0.0lf;
    dvec3 grad = shepard ? (grad_s[h] * fw - fs * grad_w[h]) / (fw * fw) : grad_s[h];
    double q = u_shepard == 0 ? fs : (fw > 0.0lf ? fs / fw : 0.0lf);
    double slope = dot(grad, dir);
    double dt = (double(u_iso_value[hit_iso[h]]) - q) / slope;
    if (slope != 0.0lf && abs(dt) <= u_lattice_k * double(hit_depth[h]))
      hit_depth[h] = float(double(hit_depth[h]) + dt);
    double len = length(grad);
    vec3 n = len > 0.0lf ? vec3(-grad / len) : vec3(0.0, 0.0, -1.0);
    vec3 normal = n.x * u_right + n.y * u_up + n.z * u_forward;
    ray.color += hit_weight[h] * vx_iso_light(hit_iso[h], normal, -world_dir);
  }
  if (first_is_hit) first_hit = hit_depth[0] * scale;

  atomicAdd(sh_counts[0], my_samples);
  atomicAdd(sh_counts[1], my_evaluations);
  atomicAdd(sh_counts[3], uint(hit_count) + unlit_count);
  atomicAdd(sh_counts[4], unlit_count);
  atomicAdd(sh_counts[5], my_skipped);
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    atomicAdd(counts[0], sh_counts[0]);
    uint old = atomicAdd(counts[1], sh_counts[1]);  // a 64-bit count in two words
    if (old + sh_counts[1] < old) atomicAdd(counts[2], 1u);
    atomicAdd(counts[3], sh_counts[2]);
    atomicAdd(counts[4], sh_counts[3]);
    atomicAdd(counts[5], sh_counts[4]);
    if (sh_overflow != 0u) atomicAdd(counts[6], 1u);
    atomicAdd(counts[7], sh_counts[5]);
  }
  if (!inside) return;
  vec3 c = ray.color + unlit;
  if (u_walls != 0 && (u_background != 0 || wall.a >= 0.0))  // render/backdrop.h's over_backdrop
    picture[p] = vec4(c + ray.transmittance * wall.rgb, 1.0);
  else
    picture[p] = u_background != 0
                     ? vec4(c + ray.transmittance * environment(u_eye, world_dir), 1.0)
                     : vec4(c, 1.0 - ray.transmittance);
  first_depth[p] = first_hit;
}
