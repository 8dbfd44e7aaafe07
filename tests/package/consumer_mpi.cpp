// An MPI solver includes voxspan/mpi.h (which includes <mpi.h>) with Voxspan::mpi alone: built
// and linked here, not run (its MPI_Init would want mpiexec's environment).
#include <voxspan/mpi.h>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  voxspan::AdapterOptions options;
  options.classify.particle_spacing = 0.01;
  const voxspan::AdapterOptions with = voxspan::with_communicator(options, MPI_COMM_WORLD);
  MPI_Finalize();
  return with.mpi_comm.has_value() ? 0 : 1;
}
