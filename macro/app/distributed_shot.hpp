#pragma once
// uhpc-macro over the ranks of MPI_COMM_WORLD (issue 49): the case's rank solvers (make_part_solver)
// stepped by a DistributedRun behind the run loop's ShotStepper. Rank 0 writes every file: at each
// output the ranks fill their own particles' field records and rank 0 gathers them in the order of
// their ids, so the one-process files are written unchanged.
// Its checkpoints are those of one process: rank 0 gathers the particles' state records and makes the
// whole body's checkpoint of them (ExplicitSolver::body_checkpoint); any rank count resumes them. Not
// yet: parallel HDF5 (rank 0 holds the body's fields at an output, its state at a checkpoint).
#include <memory>

#include "case_config.hpp"
#include "material_factory.hpp"
#include "shot_stepper.hpp"

namespace uhpc::macro {

#ifdef UHPC_WITH_MPI
// The ranks of MPI_COMM_WORLD and this one's place: 1 and 0 when MPI was not started (uhpc-macro
// without a launcher).
int world_ranks();
int world_rank();

// The case over the ranks (collective). `settings`, `body` and `law` must outlive the result.
std::unique_ptr<ShotStepper> make_distributed_shot(const CaseSettings& settings, const ParticleBody& body,
                                                   const MaterialSet& law);
#else
inline int world_ranks() { return 1; }  // a build without MPI (UHPC_MPI=OFF) runs on one
inline int world_rank() { return 0; }
#endif

}  // namespace uhpc::macro
