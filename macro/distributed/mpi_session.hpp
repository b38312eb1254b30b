#pragma once
// MPI for the life of a program (MPI_Init_thread with funneled threads: OpenMP inside a rank, MPI
// from its master thread), and the rank's place in MPI_COMM_WORLD. A program started without mpirun
// is one rank.
#include <mpi.h>

namespace uhpc::macro::distributed {

class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace uhpc::macro::distributed
