#pragma once
// Checkpoints of a uhpc-macro run (run.checkpoint_interval_steps > 0): DIR/checkpoint.h5 holds the
// solver's state after a step (ExplicitSolver::checkpoint) and the run's own books (the history rows,
// the outcome and balance trackers, the field steps written), so that `uhpc-macro --restart` goes on
// from it bit for bit. The file is replaced atomically: a run killed while writing one keeps the one
// before. A checkpoint is refused (InputError) by a program of another build or for another case: the
// bytes of the states are this build's, and the state belongs to its case.
#include <filesystem>
#include <string>

#include "run_outputs.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {

struct RunCheckpoint {
  SolverCheckpoint solver;
  std::string history_text;
  std::size_t history_rows = 0;
  ImpactTracker impact;
  BalanceTracker balance;
  FieldOutputState fields;
  std::string config_hash;  // of the run's case and every file it read (run_inputs.hpp)
  std::string build;        // the program's version and commit
};

// The program build a checkpoint must come from to be resumed: "<version> <commit>".
std::string checkpoint_build();

void write_checkpoint(const std::filesystem::path& file, const RunCheckpoint& checkpoint);
// Throws InputError (naming the file) for a missing, corrupt or foreign checkpoint, and when its case
// hash differs from `config_hash`.
RunCheckpoint read_checkpoint(const std::filesystem::path& file, const std::string& config_hash);

}  // namespace uhpc::macro
