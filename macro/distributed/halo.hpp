#pragma once
// A rank's ghosts: copies of the particles of other ranks that its particles' rows may read. Particle
// j is sent to every other rank whose region meets the cube of half-width reach[j] about x_j, so any
// particle within reach[j] of a point of that region arrives there (a superset: the cube holds the
// ball). With reach_j = a_j + a_max + 2 s (support radii a, the largest a_max, the Verlet skin s) a rank
// holds every candidate node of every row that touches one of its particles: row L touches owned J when
// |x_L - x_J| < a_J, and L's candidates K lie within a_K + 2 s of x_L. So it builds each of those rows
// itself, in the serial code's order, instead of adding other ranks' partial sums, and its particles'
// forces are the serial ones bit for bit (verification.MacroDistributedRows; docs/cluster.md). The
// owners' regions must be the partition's current ones (migrate first).
#include <memory>
#include <vector>

#include "distributed/particle_partition.hpp"
#include "distributed/particle_set.hpp"
#include "distributed/transfer.hpp"

namespace uhpc::macro::distributed {

class Halo {
 public:
  // Collective. reach: one a particle of `owned`, in its order.
  Halo(const ParticlePartition& partition, const ParticleSet& owned, const std::vector<double>& reach);
  // The ghosts' ids and values (sorted by id); none of them is owned here.
  const ParticleSet& ghosts() const { return ghosts_; }
  // The owners' current values into the ghosts (the same particles, e.g. each step). Collective.
  void refresh(const ParticleSet& owned) { transfer_->refresh(owned, ghosts_); }

 private:
  std::unique_ptr<Transfer> transfer_;
  ParticleSet ghosts_;
};

}  // namespace uhpc::macro::distributed
