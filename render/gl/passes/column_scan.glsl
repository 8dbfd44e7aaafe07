// render/gl/passes/column_scan.glsl - turns one pixel's voxel column into spans ([ZD15] sec.
// 3.1, 3.2, 4.3, 4.4). Shared by both compress passes so that they find the same spans.
//   - words are scanned with findLSB on masked words, so a run costs O(1) however long it is;
//   - a gap closes when it is shorter than u_gap along the ray, in world units, measured between
//     the centres of the voxels on either side (sec. 3.2, 4.4);
//   - the ray marches through the simulation grid at the same time: voxels wholly inside
//     inner-empty cells are empty (whole chunks inside are not even read), voxels touching
//     inner-full cells are full (sec. 4.3).
// The including pass defines column_chunk() (its bit buffer) and on_span() (what to do with
// each span found, in depth order).

#include "render/gl/passes/cell_march.glsl"

uniform float u_gap;  // g, world units along the ray; 0 = no bridging
uniform float u_center_gap_scale;  // 1 + K_d / 2
uniform float u_edge_offset;  // where a span's ends lie in its end voxels: 0 outer faces, 0.5 centres

uvec4 column_chunk(uint chunk);
void on_span(uint index, float entry, float exit);

struct ColumnRuns {
  float scale;      // ray length per unit depth
  bool in_run;      // the last bit seen was set
  bool pending;     // a span has started and not been emitted
  uint start, end;  // its first layer and (once its run ended) the layer after its last
  uint found;
  float inside;
  bool clipped;     // the pending run reached the end of the scanned range
};

void emit_span(inout ColumnRuns s) {
  // A run of one voxel keeps its faces (its centre would be an empty span), and so do ends at
  // the near plane or the end of the range: they are clipped there, no surface.
  float offset = s.end - s.start > 1u ? u_edge_offset : 0.0;
  float entry = layer_depth_at(float(s.start) + (s.start > 0u ? offset : 0.0));
  float exit = layer_depth_at(float(s.end) - (s.clipped ? 0.0 : offset));
  on_span(s.found, entry, exit);
  s.inside += (exit - entry) * s.scale;
  ++s.found;
}

// Sec. 3.2: the gap is the distance between the last set voxel and the next one, centre to
// centre (an unbiased estimate of the true gap, which lies anywhere between the two voxels);
// centres of layers i and j lie (d_j - d_i)(1 + K_d / 2) apart.
void run_begins(inout ColumnRuns s, uint layer) {
  if (s.pending) {
    float gap = (layer_depth(layer) - layer_depth(s.end - 1u)) * u_center_gap_scale * s.scale;
    if (gap < u_gap) return;  // bridged
    emit_span(s);
  }
  s.pending = true;
  s.start = layer;
}

void scan_word(inout ColumnRuns s, uint bits, uint first_layer) {
  uint pos = 0u;
  for (;;) {
    if (s.in_run) {
      uint zeros = ~bits & (0xFFFFFFFFu << pos);
      if (zeros == 0u) return;
      pos = uint(findLSB(zeros));
      s.end = first_layer + pos;
      s.in_run = false;
    } else {
      uint ones = bits & (0xFFFFFFFFu << pos);
      if (ones == 0u) return;
      pos = uint(findLSB(ones));
      run_begins(s, first_layer + pos);
      s.in_run = true;
    }
  }
}

// A run of inner cells as a layer range: kind, first and last layer (lo > hi: none).
struct LayerRun {
  uint kind;
  int lo, hi;
};

LayerRun next_layer_run(inout CellMarch m) {
  LayerRun r = LayerRun(kRunNone, 1, 0);
  uint kind;
  float z_in, z_out;
  while (march_next_run(m, kind, z_in, z_out)) {
    int last = int(u_layers) - 1;
    if (kind == kRunFull) {
      // Every voxel the stretch touches, as a chord would set them.
      r = LayerRun(kind, int(layer_index(z_in)), int(layer_index(z_out)));
    } else {
      // Only voxels wholly inside: boundary voxels keep what the particles set.
      r = LayerRun(kind, max(int(ceil(layer_of(z_in))), 0),
                   min(int(floor(layer_of(z_out))) - 1, last));
    }
    if (r.lo <= r.hi) return r;
  }
  return LayerRun(kRunNone, 1, 0);
}

// Scans chunks [first_chunk, last_chunk] of the column of `pixel` (the depth range that can
// hold fluid: render/gl/passes/depth_bounds.glsl); returns the number of spans found and their
// total length along the ray in `inside`.
uint scan_column(ivec2 pixel, uint first_chunk, uint last_chunk, out float inside) {
  ColumnRuns s = ColumnRuns(ray_scale(pixel), false, false, 0u, 0u, 0u, 0.0, false);
  float z0 = max(u_near, layer_depth(first_chunk * 128u));
  float z1 = min(u_grid_far, layer_depth((last_chunk + 1u) * 128u));
  CellMarch march = march_begin(u_eye, world_ray(pixel), z0, z1);
  LayerRun run = next_layer_run(march);
  for (uint c = first_chunk; c <= last_chunk; ++c) {
    int lo = int(c * 128u);
    bool covered = run.kind != kRunNone && run.lo <= lo && run.hi >= lo + 127;
    uvec4 chunk = covered ? (run.kind == kRunFull ? uvec4(0xFFFFFFFFu) : uvec4(0u))
                          : column_chunk(c);
    for (int k = 0; k < 4; ++k) {
      int wlo = lo + 32 * k, whi = wlo + 31;
      uint bits = chunk[k];
      while (run.kind != kRunNone && run.lo <= whi) {
        if (run.hi >= wlo) {
          uint mask = bit_range_mask(uint(max(run.lo, wlo) - wlo), uint(min(run.hi, whi) - wlo));
          bits = run.kind == kRunFull ? (bits | mask) : (bits & ~mask);
        }
        if (run.hi > whi) break;
        run = next_layer_run(march);
      }
      scan_word(s, bits, uint(wlo));
    }
  }
  // A run reaching the end of the range ends there: nothing is set beyond it.
  if (s.in_run) {
    s.end = (last_chunk + 1u) * 128u;
    s.clipped = true;
  }
  if (s.pending) emit_span(s);
  inside = s.inside;
  return s.found;
}
