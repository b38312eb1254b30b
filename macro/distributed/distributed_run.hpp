#pragma once
// One explicit run over the ranks of a communicator (issue 49). Each rank steps an ExplicitSolver over
// its own particles and their ghosts (RankShare: owner computes, so an owned particle's step is the
// one-process step bit for bit, at one thread a rank), and after every step the owners overwrite their
// ghosts. The halo is made for a motion of one Verlet skin s (distributed_run.cpp): once a particle could
// have moved that far by the end of the next step, the particles go to their regions' ranks (a migrate, or a new balance past the partition's
// threshold), and the halo and the rank's solver are made again from the particles' records.
// Lazy rows travel with their particles: at a halo build each rank takes its particles' rows from the
// solvers of their former owners, and after a new slot layout its ghosts' rows from their owners. Not
// yet (ExplicitSolver::set_rank_share refuses them): the penalty contact, the Midpoint strain
// configuration (docs/cluster.md). uhpc-macro steps it through
// app/distributed_shot.cpp.
// Every call is collective and assumes every rank gets through it: a caller that catches an exception
// on one rank must end the job (MPI_Abort), as the others may be waiting for it.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <mpi.h>

#include "distributed/halo.hpp"
#include "distributed/mpi_session.hpp"
#include "distributed/particle_partition.hpp"
#include "distributed/particle_set.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro::distributed {

class DistributedRun {
 public:
  // The case's solver over the body's particles `ids` (ascending global ids), in their order, with its
  // conditions set and not initialized. It must give every particle the state the whole body's solver
  // gives it (positions, initial velocities, walls and prescribed velocities judged on the whole body).
  using SolverFactory = std::function<ExplicitSolver(const std::vector<std::uint32_t>& ids)>;

  // Collective: partitions the body (`total` particles) and initializes every rank's solver.
  DistributedRun(MPI_Comm comm, std::size_t total, SolverFactory factory, PartitionOptions options = {});
  DistributedRun(const DistributedRun&) = delete;
  DistributedRun& operator=(const DistributedRun&) = delete;

  // One step on every rank (ExplicitSolver::step), the ghosts refreshed, the halo made again when due.
  // Collective; false on every rank when the step failed (the solvers are back at the last good state).
  bool step();
  // Goes on from a checkpoint of the whole body (ExplicitSolver::resume_part on every rank, then the
  // particles to their regions and a new halo). Collective; std::invalid_argument for one of another body.
  void resume(const SolverCheckpoint& checkpoint);
  // Every rank's rows dropped, to be built afresh at the next step, as one process drops its own where it
  // writes a checkpoint (ExplicitSolver::drop_shape_cache). Collective by convention.
  void drop_rows() { solver_->drop_shape_cache(); }

  const ExplicitSolver& solver() const { return *solver_; }
  // The rank's particles' global ids in the solver's order (owned and ghosts), and whether each is owned.
  const std::vector<std::uint32_t>& local_ids() const { return local_ids_; }
  const std::vector<std::uint8_t>& owned() const { return owned_mask_; }
  // The owned particles' current records: the solver's record (ExplicitSolver::write_particle), then
  // the support radius; sorted by id.
  const ParticleSet& owned_records();
  std::size_t halo_builds() const { return halo_builds_; }
  double halo_build_seconds() const { return halo_build_s_; }  // wall time in them, this rank
  // The ghosts' rows taken from their owners after a new slot layout between halo builds, and the wall
  // time in it on this rank.
  std::size_t row_exchanges() const { return row_exchanges_; }
  double row_exchange_seconds() const { return row_exchange_s_; }
  std::size_t balances() const { return partition_.balances(); }
  // Lazy rows built and kept on this rank over the run (ShapeCache::rows_built, rows_kept of its solvers).
  std::size_t rows_built() const { return rows_built_ + solver_->shapes().rows_built; }
  std::size_t rows_kept() const { return rows_kept_ + solver_->shapes().rows_kept; }
  // The ids of the rank's own particles that move as rigid fragments now, ascending (ShapeCache::fragment;
  // after a halo build whose solver has built no rows yet, those of the solver it replaced).
  std::vector<std::uint32_t> owned_fragments() const;
  double skin() const { return skin_m_; }

 private:
  void build_local(bool from_records);  // the halo and the rank's solver from owned_ (collective)
  void pack_owned();                     // the solver's owned particles into owned_
  void refresh_ghosts();                 // the owners' values into the ghosts (collective)
  void rows_from_their_owners();         // lazy rows: every row as its owner holds it (collective)
  std::int32_t local_index(std::uint32_t id) const;  // in the solver, -1: not here
  // The largest motion of a particle since the halo plus its travel in the next step, over the ranks
  // (collective): the halo is good while it is within the skin.
  double reach_after_next_step() const;

  CommunicatorCopy comm_;
  SolverFactory factory_;
  ParticlePartition partition_;
  std::size_t total_ = 0;                      // the body's particles
  std::unique_ptr<ExplicitSolver> solver_;
  std::unique_ptr<Halo> halo_;
  ParticleSet owned_;                          // the owned particles' records, sorted by id
  std::vector<std::uint32_t> local_ids_;       // the solver's particles' ids
  // Each global id's place in the solver, -1 where not on this rank: one int a particle of the body (as
  // rows_from_owners' owner map), for the rows' millions of node lookups at each installation.
  std::vector<std::int32_t> local_of_id_;
  std::vector<std::uint8_t> owned_mask_;       // one a solver particle
  std::vector<std::size_t> owned_at_, ghost_at_;  // where owned_ and the halo's ghosts are in the solver
  std::vector<std::uint32_t> sent_;            // the rows of owned_ that are other ranks' ghosts
  std::vector<double> x_at_halo_;              // the solver's positions when the halo was made
  double skin_m_ = 0.0, cell_m_ = 0.0;         // s and the reach maps' cell
  double kept_row_reach_m_ = 0.0;              // the halo's room for kept lazy rows
  std::size_t halo_builds_ = 0;
  std::size_t rows_built_ = 0, rows_kept_ = 0;  // those of the solvers replaced so far
  std::vector<std::uint32_t> fragments_at_build_;  // owned_fragments() of the solver last replaced
  double halo_build_s_ = 0.0;
  std::size_t row_exchanges_ = 0;
  double row_exchange_s_ = 0.0;
};

}  // namespace uhpc::macro::distributed
