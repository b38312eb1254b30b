// uhpc-macro: one 3D penetration run (docs/architecture.md section 2).
//
//   uhpc-macro --config CASE.json [--sdel sdel.json] [--set key.path=value]... --out DIR [-q] [--restart | --reuse | --reuse-check | --restart-check]
//              [--checkpoint-every-min M]
//   uhpc-macro --config CASE.json [--sdel sdel.json] [--set key.path=value]... --inputs-hash
//
// Writes DIR/result.json, DIR/history.csv and DIR/fields.h5 + DIR/fields.xdmf (ParaView); on a
// numerical failure, the last good state in fields.h5 and DIR/diagnostic.json (exit code 1). Bad input:
// one line naming the file, key and reason, exit code 2. See macro/README.md.
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "macro_run.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/logging.hpp"
#ifdef UHPC_WITH_MPI
#include "distributed/mpi_session.hpp"
#endif

namespace {
#ifdef UHPC_WITH_MPI
using MaybeMpi = std::optional<uhpc::macro::distributed::MpiSession>;
int rank_count(const MaybeMpi& mpi) { return mpi ? mpi->size() : 1; }
int rank_of(const MaybeMpi& mpi) { return mpi ? mpi->rank() : 0; }
#else
struct MaybeMpi {};  // a build without MPI (UHPC_MPI=OFF): one process
int rank_count(const MaybeMpi&) { return 1; }
int rank_of(const MaybeMpi&) { return 0; }
#endif
}  // namespace

int main(int argc, char** argv) {
  // Started by mpirun or srun as one of several ranks, the ranks share the run (distributed_shot.hpp);
  // otherwise it is one process and MPI is not started.
  MaybeMpi mpi;
#ifdef UHPC_WITH_MPI
  try {
    if (uhpc::macro::distributed::started_as_one_of_several_ranks()) mpi.emplace(&argc, &argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: MPI did not start (%s): run without a launcher, or check the MPI installation\n", e.what());
    return uhpc::kExitNumerical;
  }
#endif
  CLI::App app{"3D explicit RKPM penetration run: a rigid sphere into a particle target (result.json, "
               "history.csv, fields.h5 + fields.xdmf).",
               "uhpc-macro"};
  uhpc::macro::MacroRunArgs args;
  std::string out;
  app.add_option("--config", args.config_path, "case configuration (JSON), e.g. data/macro_elastic_block.json")
      ->required();
  app.add_option("--sdel", args.sdel_path, "SDEL handoff (sdel.json); validated, used by laws with the SDEL");
  app.add_option("--out", out, "output directory (required unless --inputs-hash)");
  app.add_flag("-q,--quiet", args.quiet, "warnings and errors only");
  app.add_flag("--restart", args.restart,
               "go on from OUT/checkpoint.h5 (written by a run of the same case, --sdel, --set and build: "
               "at run.checkpoint_interval_steps, --checkpoint-every-min, or at an undecided end) instead of "
               "starting at t = 0");
  double checkpoint_every_min = 0.0;
  app.add_option("--checkpoint-every-min", checkpoint_every_min,
                 "write OUT/checkpoint.h5 every this many minutes of wall time (0: never), so that a killed run "
                 "goes on with --restart; not an input of the run (its numbers do not change), and a run "
                 "resumed from such a checkpoint differs from the unstopped one within "
                 "solver.shape_reuse_tolerance");
  app.add_flag("--inputs-hash", args.inputs_hash,
               "print the hash of this run's inputs (the case with --set, the files it reads: result.json's "
               "provenance.config_hash), then on a second line the same in the scheme before 2026-12-06 "
               "(the case's notes hashed too), and exit, writing nothing");
  auto* reuse = app.add_flag("--reuse", args.reuse,
               "keep a finished run already in OUT when its result.json was made from these inputs (the same "
               "provenance.config_hash); exit 2 when it was made from other inputs");
  reuse->excludes(app.get_option("--restart"));
  auto* reuse_check = app.add_flag("--reuse-check", args.reuse_check,
               "print \"kept\" when OUT holds a finished run of these inputs, \"run\" when it holds none, exit 2 "
               "when it holds one of other inputs; writes nothing");
  reuse_check->excludes(app.get_option("--restart"));
  auto* restart_check = app.add_flag("--restart-check", args.restart_check,
               "print \"restart\" when OUT/checkpoint.h5 can be gone on from with these inputs (this build's, "
               "before the end time), \"start\" when there is none or another build wrote it; exit 2 for one of "
               "other inputs, a corrupt one or one at or past the end time; writes nothing");
  restart_check->excludes(app.get_option("--restart"));
  restart_check->excludes(reuse);
  restart_check->excludes(reuse_check);
  uhpc::add_set_option(app, args.overrides);
  // Over several ranks, the failures every rank meets alike (the command line, the inputs, a failed step)
  // are told by rank 0 alone: the others return quietly.
  [[maybe_unused]] bool told_by_rank_0 = false;
  const bool quiet_rank = rank_of(mpi) > 0;
  const int code = uhpc::run_main(app, [&] {
    try {
      app.parse(argc, argv);
      if (out.empty() && !args.inputs_hash) throw CLI::RequiredError("--out");
      uhpc::init_logging("uhpc-macro", args.quiet ? uhpc::Verbosity::Quiet : uhpc::Verbosity::Normal);
      args.out = out;
      if (!(checkpoint_every_min >= 0.0 && std::isfinite(checkpoint_every_min)))
        throw uhpc::InputError(fmt::format("--checkpoint-every-min {}: not a number of minutes >= 0 (0: none)",
                                           checkpoint_every_min));
      args.checkpoint_every_s = 60.0 * checkpoint_every_min;
      uhpc::macro::run_macro(args);
      return uhpc::kExitOk;
    } catch (const CLI::ParseError& e) {
      if (!quiet_rank) throw;
      told_by_rank_0 = true;
      return e.get_exit_code() == 0 ? uhpc::kExitOk : uhpc::kExitBadInput;  // --help, --version: 0
    } catch (const uhpc::InputError&) {
      if (!quiet_rank) throw;
      told_by_rank_0 = true;
      return uhpc::kExitBadInput;
    } catch (const uhpc::NumericalError&) {
      if (!quiet_rank) throw;
      told_by_rank_0 = true;
      return uhpc::kExitNumerical;
    }
  });
#ifdef UHPC_WITH_MPI
  // Rank 0, or a rank that stops alone (an internal error), ends the job with its exit code: the others
  // may be waiting for it in the run.
  if (code != uhpc::kExitOk && rank_count(mpi) > 1 && !told_by_rank_0) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  return code;
}
