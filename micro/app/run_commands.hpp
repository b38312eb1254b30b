#pragma once
// The drivers of `uhpc-micro run` (one cell) and `uhpc-micro ensemble` (sizes x realizations): configs
// in, the cell generated and meshed, the analyzer run, energy bridging and the ensemble statistics,
// files out. The analyzer comes from outside (cell_analyzer.hpp): these drivers do not depend on the
// fracture solver.
//
// Both throw InputError for bad input (exit 2 through run_main) and NumericalError after writing their
// results when the analysis failed (exit 1): `run` for a failed cell, `ensemble` when a size is left
// without any usable cell.
//
// Config keys (data/micro_run.json; data/micro_analysis_ensemble.json adds the ensemble's), all required:
//   cell_config                    the cell config (relative to this file), read as `generate` reads it
//   bridging.strain_control        first_passage | max_below    ([choice], energy_bridging.hpp)
//   bridging.damage_measure        energy | force               ([choice]: which d drives the curves)
//   bridging.tolerance             (0, 1), 0.01: |d_energy - d_force| above it is flagged in summary.json
//   strain_grid.max_strain         (0, 1), 1.5e-3: the common grid [0, max] ...
//   strain_grid.points             [2, 1e6], 301: ... with this many even points
//   analysis                       object handed to the analyzer factory (its keys are the solver's)
//   ensemble only: cell_sizes_m (strictly ascending), realizations [1, 10000], base_seed [0, 2^53),
//   retry_failed (true: a failed cell is run again on a rerun; false: its record is kept),
//   max_operator_mismatch (> 0, 0.05 shipped: a cell whose operator_energy_mismatch exceeds it is
//   suspect, excluded from the mean and listed with it; the healthy cells measured sit near 1e-2)
//   notes                          free text
//
// Per cell: cell.json (the generated cell), curves.h5 (per state: states/{strain, sigma_bar [Pa],
// bulk_energy, cohesive_energy, dissipated_energy, external_work [J/m], max_opening [m],
// crack_segments, open_segments, newton_iterations, psi_bar, psi_0 [J/m^3], d_energy, d_force,
// cracked}; controlled/{strain, damage, stress}: the strain-controlled curve's vertices;
// resampled/{strain, damage, stress} on the grid (attribute valid_points); root attributes status,
// diagnostic, E0_bar_Pa, side_m, provenance) and summary.json (status, diagnostic, E0_bar, peak
// stress and its strain, strain at d = 0.5, dissipated energy, energy balance, bridging check, steps,
// Newton iterations, snap-back, node/DOF counts, wall time, cell_hash, post_hash, provenance).
// summary.json is written last: its presence with the same cell_hash marks a finished cell.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cell_analyzer.hpp"

namespace uhpc::micro {

// `uhpc-micro run --config data/micro_run.json --out DIR`: DIR/cell.json, DIR/curves.h5, DIR/summary.json.
// Overrides: "cell.<key>=v" reach the cell config, "microstructure.<key>=v" its microstructure file,
// the rest (including "analysis.<key>=v") the run config.
int run_cell_command(const std::string& config_path, const std::vector<std::string>& overrides,
                     const std::filesystem::path& out, const CellAnalyzerFactory& factory);

// `uhpc-micro ensemble --config data/micro_analysis_ensemble.json --out DIR [-j N]`:
// DIR/size_<l>mm/cell_<NN>/{cell.json, curves.h5, summary.json}, DIR/ensemble.h5, DIR/summary.json.
// `jobs` cells are analysed at once (<= 0: one per hardware thread). Resumable: a cell whose
// summary.json carries the same cell hash is reloaded, not run again (failed cells are run again
// when retry_failed is true). Same overrides as `run`.
//
// A selection runs part of the ensemble, for one batch job per cell or per size on a cluster
// (docs/cluster.md): only_size_mm (one of cell_sizes_m, in mm) and only_cell (a realization index,
// of every size or of the selected one) analyse the selected cells only, resume as above, and write
// neither ensemble.h5 nor DIR/summary.json; assemble_only analyses nothing: every cell must be
// finished on disk (failed cells count as failed, whatever retry_failed says), and ensemble.h5 and
// summary.json are written from them. A size or index outside the ensemble, a selection with
// assemble_only, or assemble_only with unfinished cells is bad input (exit 2).
//
// A cell selection (cell_selection, with assemble_only and assemble_to) assembles a resampled ensemble,
// e.g. one bootstrap sample (pipelines/uq_sdel.py, docs/uq-sdel.md): the file lists, per size, the
// realizations averaged, each as often as it is listed (with multiplicities), and ensemble.h5 and
// summary.json go to assemble_to instead of DIR (the cells are reloaded from DIR as --assemble-only
// reloads them, each locked while it is read; the full ensemble's files there are left alone). The averaging is the full ensemble's, draw by draw: a failed, suspect or
// incomplete cell drawn k times counts k times as such and is left out of the mean. Format
// ("uhpc-cell-selection/1", every key required but notes):
//   {"format": "uhpc-cell-selection/1", "notes": "...",
//    "sizes": [{"cell_size_m": 0.003, "realizations": [4, 4, 17, ...]}, ...]}
// with one entry per size of the config, in its order, each listing at least one realization in
// [0, realizations). Only the cells drawn must be finished. Bad input (exit 2, naming the file and key):
// a missing or unreadable file, another format, a size missing, extra or out of order, a realization out
// of range or not an integer, an unknown key; a selection without assemble_only or assemble_to.
struct EnsembleSelection {
  std::optional<double> only_size_mm;
  std::optional<long long> only_cell;
  bool assemble_only = false;
  std::optional<std::filesystem::path> cell_selection;  // --select FILE
  std::optional<std::filesystem::path> assemble_to;     // --assemble-to DIR
};

int run_ensemble_command(const std::string& config_path, const std::vector<std::string>& overrides,
                         const std::filesystem::path& out, int jobs, const CellAnalyzerFactory& factory,
                         const EnsembleSelection& selection = {});

}  // namespace uhpc::micro
