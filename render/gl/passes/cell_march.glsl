// render/gl/passes/cell_march.glsl - walks a pixel's ray through the simulation grid's cell states
// (3D DDA) and yields the runs of inner cells, for the compress pass to skip inner-empty and
// fill inner-full stretches ([ZD15] sec. 4.3). Same cell rule as render/cell_march.h.
// The cell states are an R8UI 3D texture (bits 0-1 occupancy, bit 2 inner:
// voxspan/cell_states.h); outside the grid is empty air. Its texture unit:
// binding::cell_state_defines().

layout(binding = CELL_STATES_UNIT) uniform usampler3D u_cells;
uniform uint u_cells_on;        // 0: no cell states this frame
uniform vec3 u_cells_origin;    // world position of cell (0, 0, 0)'s corner
uniform float u_cells_size;     // cell edge length
uniform ivec3 u_cells_dims;

const uint kRunNone = 0u;
const uint kRunEmpty = 1u;  // inner-empty cells: no fluid
const uint kRunFull = 2u;   // inner-full cells: all fluid

struct CellMarch {
  ivec3 cell, step;
  vec3 next, delta;  // depth of the next boundary per axis; depth per cell per axis
  float z, z_end;    // current depth; end of the march
  bool running;
};

uint cell_run_kind(ivec3 cell) {
  uint s = texelFetch(u_cells, cell, 0).r;
  if ((s & 4u) == 0u) return kRunNone;
  uint occupancy = s & 3u;
  return occupancy == 0u ? kRunEmpty : (occupancy == 2u ? kRunFull : kRunNone);
}

// Whether the point lies in an inner-full cell.
bool inner_full_at(vec3 p) {
  if (u_cells_on == 0u) return false;
  ivec3 c = ivec3(floor((p - u_cells_origin) / u_cells_size));
  if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, u_cells_dims))) return false;
  return cell_run_kind(c) == kRunFull;
}

// Starts the march of the ray eye + z * ray over [z0, z1], clipped to the grid's box.
CellMarch march_begin(vec3 eye, vec3 ray, float z0, float z1) {
  CellMarch m;
  m.running = false;
  m.cell = ivec3(0);
  m.step = ivec3(1);
  m.next = vec3(0.0);
  m.delta = vec3(0.0);
  m.z = z0;
  m.z_end = z1;
  if (u_cells_on == 0u) return m;
  vec3 lo = u_cells_origin, hi = u_cells_origin + vec3(u_cells_dims) * u_cells_size;
  for (int a = 0; a < 3; ++a) {
    if (ray[a] == 0.0) {
      if (eye[a] < lo[a] || eye[a] >= hi[a]) return m;
      continue;
    }
    float ta = (lo[a] - eye[a]) / ray[a], tb = (hi[a] - eye[a]) / ray[a];
    m.z = max(m.z, min(ta, tb));
    m.z_end = min(m.z_end, max(ta, tb));
  }
  if (!(m.z < m.z_end)) return m;
  vec3 start = (eye + m.z * ray - u_cells_origin) / u_cells_size;
  for (int a = 0; a < 3; ++a) {
    m.cell[a] = clamp(int(floor(start[a])), 0, u_cells_dims[a] - 1);
    m.step[a] = ray[a] > 0.0 ? 1 : -1;
    if (ray[a] == 0.0) {
      m.next[a] = 3.0e38;
      m.delta[a] = 3.0e38;
    } else {
      float boundary = u_cells_origin[a] + float(m.cell[a] + (ray[a] > 0.0 ? 1 : 0)) * u_cells_size;
      m.next[a] = (boundary - eye[a]) / ray[a];
      m.delta[a] = u_cells_size / abs(ray[a]);
    }
  }
  m.running = true;
  return m;
}

// The next maximal run of inner cells of one kind along the ray: its kind and depth range.
// False when the ray has left the grid.
bool march_next_run(inout CellMarch m, out uint kind, out float z_in, out float z_out) {
  kind = kRunNone;
  z_in = 0.0;
  z_out = 0.0;
  while (m.running && m.z < m.z_end) {
    uint k = cell_run_kind(m.cell);
    if (kind != kRunNone && k != kind) return true;  // this cell starts something else
    int a = m.next.x < m.next.y ? (m.next.x < m.next.z ? 0 : 2) : (m.next.y < m.next.z ? 1 : 2);
    float leave = min(m.next[a], m.z_end);
    if (k != kRunNone) {
      if (kind == kRunNone) z_in = m.z;
      kind = k;
      z_out = leave;
    }
    m.z = leave;
    m.cell[a] += m.step[a];
    m.next[a] += m.delta[a];
    if (m.cell[a] < 0 || m.cell[a] >= u_cells_dims[a]) m.running = false;
  }
  return kind != kRunNone;
}
