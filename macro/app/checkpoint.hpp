#pragma once
// Checkpoints of a uhpc-macro run (run.checkpoint_interval_steps > 0, --checkpoint-every-min, or the last
// state of an undecided run): DIR/checkpoint.h5 holds the solver's state after a step
// (ExplicitSolver::checkpoint) and the run's own books (the history rows, the outcome and balance
// trackers, the field steps written), so that `uhpc-macro --restart` goes on from it (bit for bit when
// the writing run dropped its lazy shape rows there, as all but the clock's checkpoints do). The file is replaced atomically: a run killed while writing one keeps the one
// before. A checkpoint is refused (InputError) by a program of another build or for another case: the
// bytes of the states are this build's, and the state belongs to its case.
#include <filesystem>
#include <string>

#include "case_config.hpp"
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
// Whether this build wrote `file`: false for another build's, and for an HDF5 file without checksums
// (every build since they were added writes them); true too when the file cannot be read or fails its
// checksums (read_checkpoint then says why).
bool written_by_this_build(const std::filesystem::path& file);
// Throws InputError (naming the file) for a missing, corrupt or foreign checkpoint, and when its case
// hash differs from `config_hash`. The file's checksums (hdf5_io.hpp) are verified: a checkpoint without
// them, or one whose metadata or values fail them, is refused.
RunCheckpoint read_checkpoint(const std::filesystem::path& file, const std::string& config_hash);

// The checkpoint's clock within the restarted run's own bounds: time finite, >= 0 and before
// run.end_time_s (and 0 only at step 0), steps in [0, run.max_steps], repeats >= 0, the step dt finite
// and > 0, the last step and the wall force finite, the last field output not after the time. Throws
// InputError naming the file, the value and the bound.
void check_checkpoint_values(const RunCheckpoint& checkpoint, const RunSettings& run, const std::filesystem::path& file);

}  // namespace uhpc::macro
