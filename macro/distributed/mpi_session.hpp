#pragma once
// MPI for the life of a program (MPI_Init_thread with funneled threads: OpenMP inside a rank, MPI
// from its master thread), and the rank's place in MPI_COMM_WORLD. A program started without mpirun
// is one rank. And a communicator's copy owned by whoever needs one for its lifetime.
#include <mpi.h>

namespace uhpc::macro::distributed {

// Whether a launcher started this process as one of several ranks of a job: the size it leaves in the
// environment before MPI starts (Open MPI's mpirun, MPICH's PMI, Slurm's srun), the first found, above
// 1. One task of srun -n1 (the pipelines' LAUNCH), or a program it starts, is not.
bool started_as_one_of_several_ranks();

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

// A duplicate of a communicator for as long as its holder lives: its messages never meet the caller's,
// and it stays valid whatever becomes of the one it was copied from. Collective to make.
class CommunicatorCopy {
 public:
  explicit CommunicatorCopy(MPI_Comm from) { MPI_Comm_dup(from, &comm_); }
  ~CommunicatorCopy() {
    if (comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
  }
  CommunicatorCopy(CommunicatorCopy&& other) noexcept : comm_(other.comm_) { other.comm_ = MPI_COMM_NULL; }
  CommunicatorCopy(const CommunicatorCopy&) = delete;
  CommunicatorCopy& operator=(const CommunicatorCopy&) = delete;
  CommunicatorCopy& operator=(CommunicatorCopy&&) = delete;
  MPI_Comm get() const { return comm_; }

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
};

}  // namespace uhpc::macro::distributed
