// The MPI tests' frame (tests only): this process's rank and the job's size in MPI_COMM_WORLD,
// and main(): every rank runs every test (the collectives need them all), rank 0 alone prints
// the report, and the job fails when a test failed on any rank.
#pragma once

#include <gtest/gtest.h>
#include <mpi.h>

namespace voxspan::test {

inline int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

inline int world_size() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// The first `ranks` ranks of the job, or MPI_COMM_NULL on the others (collective).
inline MPI_Comm first_ranks(int ranks) {
  MPI_Comm comm = MPI_COMM_NULL;
  MPI_Comm_split(MPI_COMM_WORLD, world_rank() < ranks ? 0 : MPI_UNDEFINED, world_rank(), &comm);
  return comm;
}

// main()'s body: MPI_Init, the tests, MPI_Finalize; the exit status of the job's worst rank.
inline int run_mpi_tests(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (world_rank() != 0)
    delete ::testing::UnitTest::GetInstance()->listeners().Release(
        ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  const int failed = RUN_ALL_TESTS();
  int any = failed;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return any;
}

}  // namespace voxspan::test
