#pragma once
// The particles' owners: Zoltan's recursive coordinate bisection (RCB, the geometric method its
// documentation recommends for particle codes) cuts space into one region a rank, the cuts kept so
// that any point or box can be asked for its rank(s). Between balances the cuts stand still and a
// particle that leaves its region moves to the region's rank (migrate); a new balance is made only
// when the ranks' counts drift apart by more than a threshold (rebalance_if_needed). Every call that
// changes the owners is collective. The partition talks on its own duplicate of the communicator, so
// its messages never meet the caller's.
#include <vector>

#include <mpi.h>

#include "distributed/mpi_session.hpp"
#include "distributed/particle_set.hpp"

struct Zoltan_Struct;

namespace uhpc::macro::distributed {

struct PartitionOptions {
  // Zoltan's IMBALANCE_TOL: each balance leaves max / mean of the ranks' counts at most this.
  double balance_tolerance = 1.02;
  // rebalance_if_needed balances again once max / mean of the counts passes this (migration alone
  // keeps the cuts, so the counts drift as the body deforms).
  double rebalance_threshold = 1.10;
};

class ParticlePartition {
 public:
  ParticlePartition(MPI_Comm comm, PartitionOptions options = {});
  ~ParticlePartition();
  ParticlePartition(const ParticlePartition&) = delete;
  ParticlePartition& operator=(const ParticlePartition&) = delete;

  // New cuts from the owned particles' positions; every particle goes to its region's rank (a particle
  // on a cut to the side rank_of gives it, not to whichever side Zoltan's median split it to).
  void balance(ParticleSet& owned);
  // The cuts kept: particles outside their rank's region go to the region's rank. After a balance.
  void migrate(ParticleSet& owned);
  // max / mean over the ranks of the owned counts (1 when the ranks hold equal shares).
  double imbalance(const ParticleSet& owned) const;
  // migrate, then balance when the imbalance passes the threshold and what the last balance reached;
  // true when it balanced.
  bool rebalance_if_needed(ParticleSet& owned);

  int rank_of(const double x[3]) const;  // the rank whose region holds x
  bool balanced() const { return balances_ > 0; }
  std::size_t balances() const { return balances_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm comm() const { return comm_.get(); }

 private:
  CommunicatorCopy comm_;
  PartitionOptions options_;
  Zoltan_Struct* zz_ = nullptr;
  int rank_ = 0, size_ = 1;
  std::size_t balances_ = 0;
  double balanced_imbalance_ = 1.0;  // what the last balance reached
  const ParticleSet* current_ = nullptr;  // what Zoltan's callbacks read during balance()
  friend struct ZoltanCallbacks;
};

}  // namespace uhpc::macro::distributed
