// uhpc-micro: the 2D microcell program.
//
//   uhpc-micro generate --config data/micro_cell.json --out DIR [--set key=value]...
//       one porous cell: DIR/cell.json (pores, seeds, porosity, RNG seed, mesh summary), DIR/cell.svg
//   uhpc-micro generate-ensemble --config data/micro_ensemble.json --out DIR [--set key=value]...
//       every size x realization: DIR/<size>/cell_NN/{cell.json,cell.svg}, DIR/statistics.json and
//       DIR/pore_histogram.csv (figure data for pipelines/plot_micro.py)
//   uhpc-micro elastic --config data/micro_elastic.json --out DIR [--set key=value]...
//       the cell of the named cell config, its elastic uniaxial tension with the RK Galerkin solver:
//       DIR/elastic.json (E0_bar, sigma_bar, energy check, counts, timing, provenance)
//
//   uhpc-micro run --config data/micro_run.json --out DIR [--set key=value]...
//       one cell's cohesive-crack analysis to separation: DIR/cell.json, DIR/curves.h5, DIR/summary.json
//   uhpc-micro ensemble --config data/micro_analysis_ensemble.json --out DIR [-j N] [--set key=value]...
//       sizes x realizations, resumable: per cell as `run`, DIR/ensemble.h5 (uhpc-calibrate's input) and
//       DIR/summary.json; [--only-size MM] [--only-cell I] analyse a part only (one batch job per cell or
//       size), --assemble-only writes ensemble.h5 and summary.json from the finished cells;
//       --assemble-only --select FILE --assemble-to DIR: a resampled ensemble (listed cells, with
//       multiplicities) into DIR
//
// --set microstructure.<key>=... overrides data/microstructure.json (Burr law, porosity, matrix);
// for generate-ensemble, elastic, run and ensemble, --set cell.<key>=... overrides the cell config.
#include <malloc.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "fracture_analyzer.hpp"
#include "generate_commands.hpp"
#include "run_commands.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/logging.hpp"

namespace {

// A crack analysis factorizes a new tangent hundreds of times per cell; UMFPACK allocates its numeric
// object (tens to hundreds of MB) each time, which glibc serves by fresh mmap: page faults and zeroed
// pages on every factorization (833k minor faults and 7 % of the CPU time on a 3.0 mm cell). Serving
// every block from one heap that is never trimmed reuses the same pages instead (47k faults). One arena
// for all threads: the ensemble's worker threads would otherwise get arenas whose large blocks are mmaps.
void keep_freed_memory_for_reuse() {
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);  // -1: as large as possible (never trim)
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory_for_reuse();
  CLI::App app{"2D porous UHPC microcells: Burr-sampled pores, crack seeds, gmsh discretization.", "uhpc-micro"};
  app.require_subcommand(1);
  std::string config_path, out;
  std::vector<std::string> overrides;
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "warnings and errors only");

  CLI::App* generate = app.add_subcommand("generate", "generate one porous cell: cell.json and cell.svg");
  generate->add_option("--config", config_path, "cell configuration (JSON), e.g. data/micro_cell.json")->required();
  generate->add_option("--out", out, "output directory")->required();
  uhpc::add_set_option(*generate, overrides);

  CLI::App* ensemble = app.add_subcommand(
      "generate-ensemble", "generate every size x realization with derived seeds, plus per-size statistics");
  ensemble->add_option("--config", config_path, "ensemble configuration (JSON), e.g. data/micro_ensemble.json")
      ->required();
  ensemble->add_option("--out", out, "output directory")->required();
  uhpc::add_set_option(*ensemble, overrides);

  CLI::App* elastic = app.add_subcommand(
      "elastic", "elastic uniaxial tension of one cell (RK Galerkin): E0_bar and the energy check in elastic.json");
  elastic->add_option("--config", config_path, "elastic analysis configuration (JSON), e.g. data/micro_elastic.json")
      ->required();
  elastic->add_option("--out", out, "output directory")->required();
  uhpc::add_set_option(*elastic, overrides);

  CLI::App* run = app.add_subcommand(
      "run", "cohesive-crack analysis of one cell to separation: curves.h5 (stress, energies, damage) and summary.json");
  run->add_option("--config", config_path, "run configuration (JSON), e.g. data/micro_run.json")->required();
  run->add_option("--out", out, "output directory")->required();
  uhpc::add_set_option(*run, overrides);

  int jobs = 0;
  CLI::App* analyse = app.add_subcommand(
      "ensemble", "cohesive-crack analysis of sizes x realizations (resumable): ensemble.h5 and summary.json");
  analyse->add_option("--config", config_path, "ensemble configuration (JSON), e.g. data/micro_analysis_ensemble.json")
      ->required();
  analyse->add_option("--out", out, "output directory")->required();
  analyse->add_option("-j,--jobs", jobs, "cells analysed at once (default: one per hardware thread)");
  uhpc::add_set_option(*analyse, overrides);
  // One batch job per cell or per size (docs/cluster.md): run a part, then assemble.
  uhpc::micro::EnsembleSelection selection;
  double only_size_mm = 0.0;
  long long only_cell = 0;
  CLI::Option* only_size_opt = analyse->add_option(
      "--only-size", only_size_mm,
      "analyse only the cells of this size (mm, one of cell_sizes_m); writes no ensemble.h5 or summary.json");
  CLI::Option* only_cell_opt = analyse->add_option(
      "--only-cell", only_cell,
      "analyse only realization I (0-based) of each size, or of --only-size's; writes no ensemble.h5 or summary.json");
  only_cell_opt->type_name("I");
  only_size_opt->type_name("MM");
  analyse
      ->add_flag("--assemble-only", selection.assemble_only,
                 "analyse nothing: write ensemble.h5 and summary.json from the finished cells (bad input if any "
                 "cell is not finished)")
      ->excludes(only_size_opt)
      ->excludes(only_cell_opt);
  // A resampled ensemble (a bootstrap sample of the cells, pipelines/uq_sdel.py): run_commands.hpp.
  std::string select_file, assemble_to;
  CLI::Option* select_opt = analyse->add_option(
      "--select", select_file,
      "with --assemble-only and --assemble-to: average, per size, the realizations this file lists, each as often as "
      "listed (uhpc-cell-selection/1)");
  select_opt->type_name("FILE");
  CLI::Option* assemble_to_opt = analyse->add_option(
      "--assemble-to", assemble_to,
      "with --assemble-only: write ensemble.h5 and summary.json to DIR instead of --out (the cells are read from --out)");
  assemble_to_opt->type_name("DIR");

  return uhpc::run_main(app, [&] {
    app.parse(argc, argv);
    uhpc::init_logging("uhpc-micro", quiet ? uhpc::Verbosity::Quiet : uhpc::Verbosity::Normal);
    if (generate->parsed()) return uhpc::micro::run_generate(config_path, overrides, out);
    if (elastic->parsed()) return uhpc::micro::run_elastic(config_path, overrides, out);
    if (run->parsed())
      return uhpc::micro::run_cell_command(config_path, overrides, out, uhpc::micro::fracture_analyzer_factory());
    if (analyse->parsed()) {
      if (only_size_opt->count() > 0) selection.only_size_mm = only_size_mm;
      if (only_cell_opt->count() > 0) selection.only_cell = only_cell;
      if (select_opt->count() > 0) selection.cell_selection = select_file;
      if (assemble_to_opt->count() > 0) selection.assemble_to = assemble_to;
      return uhpc::micro::run_ensemble_command(config_path, overrides, out, jobs,
                                               uhpc::micro::fracture_analyzer_factory(), selection);
    }
    return uhpc::micro::run_generate_ensemble(config_path, overrides, out);
  });
}
