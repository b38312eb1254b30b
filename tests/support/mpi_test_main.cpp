// main() of the tests run under mpirun: MPI around GoogleTest, failures printed on the rank that saw
// them, every rank exiting with the worst result.
#include <gtest/gtest.h>
#include <mpi.h>

#include "distributed/mpi_session.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // An exception on one rank ends its process (and mpirun the job) instead of leaving the others
  // waiting in a collective.
  ::testing::GTEST_FLAG(catch_exceptions) = false;
  uhpc::macro::distributed::MpiSession mpi(&argc, &argv);
  const int mine = RUN_ALL_TESTS();
  int worst = 0;
  MPI_Allreduce(&mine, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return worst;
}
