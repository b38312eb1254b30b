#pragma once
// A rank's ghosts: copies of the particles of other ranks that its rows may read. Particle K goes to
// every other rank holding a particle J with |x_K - x_J| < node_reach_K + row_reach_J, judged from
// that rank's ReachMap (a superset). For owner computes (each rank builds every row that touches one
// of its particles itself, in the serial code's order, instead of adding other ranks' partial sums):
//   node_reach_K = a_K + 2 s,   row_reach_J = a_J
// (support radii a, s the Verlet skin): row L touches J when |x_L - x_J| < a_J and its nodes K lie within
// a_K of x_L, so |x_K - x_J| < a_K + a_J; the 2 s is the room for K and J to move by up to s each
// before the halo is made again (DistributedRun). The rank's particles' forces are then the serial ones
// bit for bit (one thread a rank: verification.MacroDistributedRows; docs/cluster.md). The maps are made from where
// the particles are, so the halo does not depend on the partition's cuts (a rank's particles may have
// left its region since the last migrate). Each particle asks every rank's map: its grid clips the
// search to nothing for a rank far away. A halo talks on its own copy of the communicator, so it may
// outlive the partition it was made with.
#include <memory>
#include <vector>

#include "distributed/mpi_session.hpp"
#include "distributed/particle_partition.hpp"
#include "distributed/particle_set.hpp"
#include "distributed/transfer.hpp"

namespace uhpc::macro::distributed {

class Halo {
 public:
  // Collective. node_reach, row_reach: one a particle of `owned`, in its order; cell: the side of the
  // reach maps' cells (about the largest support radius).
  Halo(const ParticlePartition& partition, const ParticleSet& owned, const std::vector<double>& node_reach,
       const std::vector<double>& row_reach, double cell);
  // The ghosts' ids and values (sorted by id); none of them is owned here.
  const ParticleSet& ghosts() const { return ghosts_; }
  // The owners' current values into the ghosts (the same particles, e.g. each step). Collective.
  void refresh(const ParticleSet& owned) { transfer_->refresh(owned, ghosts_); }
  // The rows of `owned` that are another rank's ghosts (refresh reads only these), ascending, once each.
  std::vector<std::uint32_t> sent_rows() const;
  // The rank's particles and its ghosts in one set of ascending ids, the order in which the serial code
  // builds its rows; owned_at (optional) receives where each owned particle went.
  ParticleSet local(const ParticleSet& owned, std::vector<std::size_t>* owned_at = nullptr) const;

 private:
  CommunicatorCopy comm_;  // the transfer's: before it, so it outlives it, and the partition
  std::unique_ptr<Transfer> transfer_;
  ParticleSet ghosts_;
};

}  // namespace uhpc::macro::distributed
