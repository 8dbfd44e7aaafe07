/* A C solver's use of the C API (compiled as C): a 4x4x4 lattice with a CSR grid. */
#include "c_api_client.h"

#include <voxspan/voxspan.h>

int c_api_client_run(c_api_client_result* out) {
  float xyz[64 * 3];
  unsigned offsets[9] = {0};
  int n = 0, cx, cy, cz, i, j, k;
  double origin[3] = {0, 0, 0};
  int dims[3] = {2, 2, 2};
  voxspan_adapter_options o;
  voxspan_adapter* a;
  voxspan_particles* p;
  voxspan_grid* g;
  voxspan_step_stats stats;
  const float* spheres = 0;
  int rc;

  /* Particles stored in cell order: cell by cell, 8 per cell. */
  for (cz = 0; cz < 2; ++cz)
    for (cy = 0; cy < 2; ++cy)
      for (cx = 0; cx < 2; ++cx) {
        for (k = 0; k < 2; ++k)
          for (j = 0; j < 2; ++j)
            for (i = 0; i < 2; ++i) {
              xyz[3 * n + 0] = 2.0f * cx + i + 0.5f;
              xyz[3 * n + 1] = 2.0f * cy + j + 0.5f;
              xyz[3 * n + 2] = 2.0f * cz + k + 0.5f;
              ++n;
            }
        offsets[cx + 2 * (cy + 2 * cz) + 1] = (unsigned)n;
      }

  voxspan_adapter_options_init(&o);
  o.particle_spacing = 1.0;
  o.validate = 1;
  a = voxspan_adapter_create(&o);
  p = voxspan_particles_create();
  g = voxspan_grid_create();
  if (!a || !p || !g) return -1;
  voxspan_particles_set_aos(p, VOXSPAN_FLOAT32, xyz, (size_t)n, 0);
  voxspan_grid_set_offsets(g, origin, 2.0, dims, VOXSPAN_UINT32, offsets);
  rc = voxspan_adapter_execute(a, 0, 0.0, p, g);
  voxspan_adapter_stats(a, &stats);
  out->status = rc;
  out->boundary = (long)stats.boundary;
  out->cells_full = (long)stats.cells_full;
  out->returned = (long)voxspan_adapter_boundary(a, &spheres);
  out->first_radius = spheres ? spheres[3] : -1.0f;

  /* A bad index type is an error with a message, not a crash. */
  out->bad_index_status = voxspan_grid_set_offsets(g, origin, 2.0, dims, 17, offsets);
  out->bad_index_message = voxspan_last_error();

  voxspan_grid_destroy(g);
  voxspan_particles_destroy(p);
  voxspan_adapter_destroy(a);
  return 0;
}
