#pragma once
// The ranks' particles in one set, sorted by id: on one rank (outputs written by one rank) or on every
// rank (checks against the whole body). Collective.
#include <mpi.h>

#include "distributed/particle_set.hpp"

namespace uhpc::macro::distributed {

constexpr int kEveryRank = -1;

// Every rank's `mine` (all of one width), on `root` (others get an empty set) or on every rank.
ParticleSet gather(const ParticleSet& mine, MPI_Comm comm, int root = kEveryRank);

}  // namespace uhpc::macro::distributed
