/* voxspan/voxspan.h - the C API, for C and Fortran solvers (C++ solvers may use it too).
 * Every function is safe to call from the solver's timestep loop: none throws or aborts;
 * failures come back as a status and a message from voxspan_last_error().
 *
 * The same calls as voxspan/adapter.h, through opaque handles:
 *
 *   voxspan_adapter_options o;
 *   voxspan_adapter_options_init(&o);
 *   o.render_every = 10;
 *   o.particle_spacing = dx;
 *   voxspan_adapter* a = voxspan_adapter_create(&o);          (NULL on error)
 *   voxspan_particles* p = voxspan_particles_create();
 *   voxspan_grid* g = voxspan_grid_create();
 *   each step:
 *     voxspan_particles_set_soa(p, VOXSPAN_FLOAT64, x, y, z, n);
 *     voxspan_grid_set_offsets(g, origin, cell_size, dims, VOXSPAN_INT32, offsets);
 *     voxspan_adapter_execute(a, step, time, p, g);            (g may be NULL: no grid)
 *
 * With the in-situ runtime (rendering and files as a YAML config says, docs/runtime.md):
 *   voxspan_adapter* a = voxspan_adapter_create_from_config(&o, "insitu.yaml");
 *   ... voxspan_adapter_execute(...) every step, voxspan_adapter_execute_last(...) on the last;
 *   voxspan_adapter_finish(a);                                  (waits for the files)
 *
 * Fortran: every function takes plain values or pointers (bind(C) interfaces with c_ptr,
 * c_int, c_int64_t, c_size_t, c_double); the options and stats structs hold only those types.
 * Pointers handed to the particle and grid handles are not copied: they must stay valid until
 * the next voxspan_adapter_execute() that uses them returns. */
#ifndef VOXSPAN_VOXSPAN_H
#define VOXSPAN_VOXSPAN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The version of the loaded library, e.g. "0.1.0". */
const char* voxspan_version(void);

/* Log level: 0 error, 1 warning, 2 info, 3 debug. */
void voxspan_set_log_level(int level);

/* The message of the latest failed call on this thread ("" when none). */
const char* voxspan_last_error(void);

/* Status codes returned by the calls below. */
enum {
  VOXSPAN_OK = 0,
  VOXSPAN_INVALID_INPUT = 1,   /* bad particles, grid or options; see voxspan_last_error() */
  VOXSPAN_PIPELINE_FAILED = 2, /* rendering or output failed */
  VOXSPAN_INTERNAL_ERROR = 3
};

/* Scalar types of positions, radii and attributes. */
enum { VOXSPAN_FLOAT32 = 0, VOXSPAN_FLOAT64 = 1 };
/* Index types of grid arrays. */
enum { VOXSPAN_INT32 = 0, VOXSPAN_UINT32 = 1, VOXSPAN_INT64 = 2, VOXSPAN_UINT64 = 3 };

typedef struct voxspan_adapter_options {
  int64_t render_every;    /* render when step % render_every == 0; 0 never (default 1) */
  double particle_spacing; /* rest spacing of the particles */
  int full_count;          /* particles in a full cell; 0: from particle_spacing */
  double full_fraction;    /* default 1 */
  double particle_radius;  /* when the particles have none; 0: particle_spacing */
  double cell_size;        /* of a grid built when the solver gives none; 0: 2 spacings */
  int validate;            /* 1: check that the grid matches the particles on every render
                              step (0: until one render step passes) */
  int include_ghosts;      /* 1 (default): compact ghost boundary particles too (not in an
                              MPI job: there each particle is its owner's) */
  int has_mpi_comm;        /* 1: the adapter runs inside an MPI job on mpi_comm (default 0) */
  int mpi_comm;            /* the communicator as its Fortran handle: MPI_Comm_c2f(comm) in C,
                              the communicator itself in Fortran */
} voxspan_adapter_options;

typedef struct voxspan_step_stats {
  int64_t step; /* the latest render step, -1 before the first */
  double time;
  int rendered; /* 1 when classification completed */
  int status;   /* VOXSPAN_OK or an error code */
  uint64_t particles, owned, boundary, dropped_nonfinite, not_in_grid;
  uint64_t cells, cells_empty, cells_partial, cells_full, cells_inner_empty, cells_inner_full;
  int full_count;
  int grid_built;
  double cell_size;
  double seconds_classify, seconds_compact, seconds_pipeline, seconds_total;
} voxspan_step_stats;

typedef struct voxspan_adapter voxspan_adapter;
typedef struct voxspan_particles voxspan_particles;
typedef struct voxspan_grid voxspan_grid;

/* --- adapter --- */
void voxspan_adapter_options_init(voxspan_adapter_options* options);
/* NULL when the options are invalid (message in voxspan_last_error()). */
voxspan_adapter* voxspan_adapter_create(const voxspan_adapter_options* options);
/* An adapter with the in-situ runtime behind it, configured by the YAML file at config_path:
 * its triggers decide the render steps (options->render_every is ignored). NULL when the
 * config, an output folder, the GL platform or the renderer cannot work; the message (naming
 * the key and line of a bad config) is in voxspan_last_error(). */
voxspan_adapter* voxspan_adapter_create_from_config(const voxspan_adapter_options* options,
                                                    const char* config_path);
/* Waits for pending outputs (files being written); destroy does it too, and so does the
 * process's exit (exit(), a return from main, Fortran's stop) for an adapter never destroyed. */
int voxspan_adapter_finish(voxspan_adapter* adapter);
/* Copies the pipeline's summary line into buffer (NUL-terminated, cut to size); returns its
 * full length ("" without a pipeline). */
size_t voxspan_adapter_summary(const voxspan_adapter* adapter, char* buffer, size_t size);
void voxspan_adapter_destroy(voxspan_adapter* adapter);
/* Compacts the named particle attribute beside the boundary particles. */
int voxspan_adapter_add_attribute(voxspan_adapter* adapter, const char* name);
/* The solver's walls and obstacles, copied (Adapter::set_scenery): the views draw them as opaque
 * solids. Given once for walls that stand still, again whenever they move. Sets *kept (may be
 * NULL) to the particles kept (those with a NaN or infinite position, or a NaN, infinite or
 * negative radius, are left out). */
int voxspan_adapter_set_scenery(voxspan_adapter* adapter, const voxspan_particles* scenery,
                                size_t* kept);
/* The per-step call; grid may be NULL (the adapter sorts the particles itself). */
int voxspan_adapter_execute(voxspan_adapter* adapter, int64_t step, double time,
                            const voxspan_particles* particles, const voxspan_grid* grid);
/* The solver's last step: as execute, and the triggers with `last` fire on it. */
int voxspan_adapter_execute_last(voxspan_adapter* adapter, int64_t step, double time,
                                 const voxspan_particles* particles, const voxspan_grid* grid);
int voxspan_adapter_is_render_step(const voxspan_adapter* adapter, int64_t step, double time);
int voxspan_adapter_stats(const voxspan_adapter* adapter, voxspan_step_stats* stats);
/* The latest render step's boundary particles: packed x, y, z, radius floats; returns the
 * count and sets *xyzr (valid until the next execute). x, y, z are measured from the point
 * voxspan_adapter_boundary_origin gives (the world's origin for ordinary scenes; a point of the
 * fluid when it lies far from it, where floats would round world coordinates coarsely). */
size_t voxspan_adapter_boundary(const voxspan_adapter* adapter, const float** xyzr);
/* The world coordinates the boundary particles' x, y, z are measured from: a particle is at
 * origin + (x, y, z), added in double. */
void voxspan_adapter_boundary_origin(const voxspan_adapter* adapter, double origin[3]);
/* The scenery kept from the last voxspan_adapter_set_scenery: packed x, y, z, radius floats;
 * returns the count and sets *xyzr (valid until the next set_scenery). */
size_t voxspan_adapter_scenery(const voxspan_adapter* adapter, const float** xyzr);
/* The latest render step's cell states (voxspan/cell_states.h bytes, x fastest). Returns the
 * number of cells. */
size_t voxspan_adapter_cell_states(const voxspan_adapter* adapter, double origin[3],
                                   double* cell_size, int dims[3], const uint8_t** states);
/* A compacted attribute of the latest render step: returns the float count, sets *values and
 * *components; 0 when the name was not asked for. */
size_t voxspan_adapter_attribute(const voxspan_adapter* adapter, const char* name,
                                 const float** values, int* components);

/* --- particles (a view of the solver's arrays) --- */
voxspan_particles* voxspan_particles_create(void);
void voxspan_particles_destroy(voxspan_particles* particles);
/* AoS: particle i's x, y, z at xyz + i * stride_bytes (stride 0: packed). */
int voxspan_particles_set_aos(voxspan_particles* particles, int type, const void* xyz, size_t count,
                              size_t stride_bytes);
int voxspan_particles_set_soa(voxspan_particles* particles, int type, const void* x, const void* y,
                              const void* z, size_t count);
int voxspan_particles_set_owned(voxspan_particles* particles, size_t owned);
int voxspan_particles_set_radius(voxspan_particles* particles, double radius);
/* Per-particle radii (stride 0: packed); NULL clears them. */
int voxspan_particles_set_radii(voxspan_particles* particles, int type, const void* radii,
                                size_t stride_bytes);
/* Adds or replaces a named attribute; the name is copied. */
int voxspan_particles_set_scalar(voxspan_particles* particles, const char* name, int type,
                                 const void* values, size_t stride_bytes);
int voxspan_particles_set_vector(voxspan_particles* particles, const char* name, int type,
                                 const void* xyz, size_t stride_bytes);
void voxspan_particles_clear_attributes(voxspan_particles* particles);

/* --- grid (a view of the solver's neighbour grid) --- */
voxspan_grid* voxspan_grid_create(void);
void voxspan_grid_destroy(voxspan_grid* grid);
/* Compact grid, CSR: cell c holds sorted slots [offsets[c], offsets[c+1]). */
int voxspan_grid_set_offsets(voxspan_grid* grid, const double origin[3], double cell_size,
                             const int dims[3], int index_type, const void* offsets);
int voxspan_grid_set_begin_end(voxspan_grid* grid, const double origin[3], double cell_size,
                               const int dims[3], int index_type, const void* begin,
                               const void* end);
/* Per-particle cell index. */
int voxspan_grid_set_cell_index(voxspan_grid* grid, const double origin[3], double cell_size,
                                const int dims[3], int index_type, const void* cell_of);
/* Geometry only: the adapter sorts the particles into it. */
int voxspan_grid_set_geometry(voxspan_grid* grid, const double origin[3], double cell_size,
                              const int dims[3]);
/* Sorted slot k holds particle order[k] (NULL: the particles are stored in cell order). */
int voxspan_grid_set_order(voxspan_grid* grid, int index_type, const void* order);
/* 1 for 1-based (Fortran) indices. */
int voxspan_grid_set_index_base(voxspan_grid* grid, int base);
/* Back to no grid. */
void voxspan_grid_clear(voxspan_grid* grid);

#ifdef __cplusplus
}
#endif

#endif /* VOXSPAN_VOXSPAN_H */
