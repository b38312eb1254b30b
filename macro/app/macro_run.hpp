#pragma once
// One uhpc-macro run: read and validate the case (and the SDEL handoff), build the target, material,
// support and projectile, step to the end time (or until shortly after the projectile leaves), and
// write result.json, history.csv and fields.h5/.xdmf into `out`. Throws InputError for bad input
// (exit code 2) and, after writing the last good state and diagnostic.json, NumericalError for a
// failed run (exit code 1).
#include <filesystem>
#include <string>
#include <vector>

namespace uhpc::macro {

struct MacroRunArgs {
  std::string config_path;
  std::vector<std::string> overrides;
  std::string sdel_path;  // empty: none
  std::filesystem::path out;
  bool quiet = false;  // no progress line
  // Go on from out/checkpoint.h5 (written by a run of the same case, --sdel and --set, and the same
  // build: at run.checkpoint_interval_steps, by the clock below, or at an undecided end) instead of
  // starting at t = 0.
  bool restart = false;
  // Write out/checkpoint.h5 every this many seconds of wall time (0: never), for --restart after a kill.
  // Not an input of the run: the checkpoints keep the shape cache, so the run's numbers do not depend on
  // when the clock fired (run.checkpoint_interval_steps, an input, drops it, so that a resumed run
  // equals the unstopped one bit for bit).
  double checkpoint_every_s = 0.0;
  // Only print the hash of the inputs (what result.json's provenance.config_hash would be) and return.
  bool inputs_hash = false;
  // A finished run already in out (its result.json) is kept when it was made from these inputs (the same
  // provenance.config_hash) and refused (InputError) when it was not: the make rules reuse runs safely.
  bool reuse = false;
  // Only say whether out holds a finished run of these inputs: prints "kept" (it does) or "run" (it holds
  // none: a run is needed), refuses (InputError) one of other inputs, and writes nothing. A launcher
  // (pipelines/launch_shot.sh) asks this before it spends a job step on a shot.
  bool reuse_check = false;
  // Only say whether out/checkpoint.h5 can be gone on from with these inputs: prints "restart" (it is this
  // build's, of these inputs, before the end time) or "start" (there is none, or another build wrote it:
  // only a run from t = 0 is left), refuses (InputError) one of other inputs, a corrupt one or one at or
  // past the end time, and writes nothing. pipelines/carried_shot.py asks it before it resumes a run.
  bool restart_check = false;
};

void run_macro(const MacroRunArgs& args);

}  // namespace uhpc::macro
