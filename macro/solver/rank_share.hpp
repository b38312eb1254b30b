#pragma once
// The solver as one rank's part of a distributed run (macro/distributed/distributed_run.hpp). It holds
// the rank's own particles and ghosts: copies of particles other ranks own, which the owners overwrite
// after every step (ExplicitSolver::write_particle, read_particle). Every row that touches an owned
// particle is built here from the ghosts (owner computes), so an owned particle's force is the
// one-process force bit for bit; a ghost's own force and stress may be wrong (its neighbours are not all
// here), and no owned particle's step reads them from such a ghost. Only the owned particles count in the stable
// step, the step's checks, the books, the domain and the sphere's contact; the ranks' values are
// combined by the functions below. They are collective: every rank calls them in the same order, so a
// step's decisions (its size, a failure, a repeat) are the same on all.
#include <cstdint>
#include <functional>
#include <vector>

namespace uhpc::macro {

struct RankShare {
  std::vector<std::uint8_t> owned;        // one a particle: 1 owned here, 0 a ghost
  std::vector<std::uint32_t> ids;         // one a particle: its global id (ascending)
  std::function<double(double)> min;      // the minimum over the ranks
  std::function<void(double*, int)> sum;  // the sums over the ranks of `count` values, in place
  // Every rank's `mine`, concatenated in rank order, into `all` on every rank.
  std::function<void(const std::vector<double>& mine, std::vector<double>& all)> gather;
  // (The functions talk on the run's communicator: a copy of the solver must not outlive the run.)
};

}  // namespace uhpc::macro
