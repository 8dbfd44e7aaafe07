/* voxspan/voxspan.h - the C API, for C and Fortran solvers (C++ solvers may use it too).
 * Every function is safe to call from the solver's timestep loop: none throws or aborts;
 * failures come back as a status and a message from voxspan_last_error(). */
#ifndef VOXSPAN_VOXSPAN_H
#define VOXSPAN_VOXSPAN_H

#ifdef __cplusplus
extern "C" {
#endif

/* The version of the loaded library, e.g. "0.1.0". */
const char* voxspan_version(void);

/* Log level: 0 error, 1 warning, 2 info, 3 debug. */
void voxspan_set_log_level(int level);

#ifdef __cplusplus
}
#endif

#endif /* VOXSPAN_VOXSPAN_H */
