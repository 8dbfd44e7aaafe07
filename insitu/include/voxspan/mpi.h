// voxspan/mpi.h - the in-situ runtime inside an MPI job: include it (it includes <mpi.h>)
// where the solver has its communicator, and hand that over:
//
//   voxspan::Adapter adapter = voxspan::adapter_from_config_file("insitu.yaml", options, comm);
//
// Every rank of `comm` makes the adapter with the same config (a rank whose config differs is
// refused at start-up, naming it and the first key that differs) and calls execute() on the
// same steps with the same step and time, its own particles (ghosts after the owned ones:
// ParticleView::with_owned) and its own grid. The views are framed on the global bounds, every
// rank voxelizes into the same grid, the span images are composited exactly (per pixel, the
// union of every rank's intervals) and shaded on rank 0, which writes the pictures; a failure
// on one rank fails the step on all (one error line, no deadlock). docs/runtime.md, "MPI".
// The library's other headers never include <mpi.h>: C and Fortran hand the communicator over
// as its Fortran handle (voxspan_adapter_options.mpi_comm).
#pragma once

#include <mpi.h>

#include <string>

#include "voxspan/insitu.h"

namespace voxspan {

inline AdapterOptions with_communicator(AdapterOptions options, MPI_Comm comm) {
  options.mpi_comm = static_cast<int>(MPI_Comm_c2f(comm));
  return options;
}

inline Adapter adapter_from_config_file(const std::string& path, AdapterOptions options,
                                        MPI_Comm comm) {
  return adapter_from_config_file(path, with_communicator(std::move(options), comm));
}

inline Adapter adapter_from_config_text(const std::string& yaml, AdapterOptions options,
                                        MPI_Comm comm,
                                        const std::string& source_name = "<config>") {
  return adapter_from_config_text(yaml, with_communicator(std::move(options), comm), source_name);
}

}  // namespace voxspan
