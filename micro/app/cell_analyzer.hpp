#pragma once
// The seam between the drivers (`uhpc-micro run`, `uhpc-micro ensemble`) and the fracture solver: the
// drivers generate and mesh a cell, hand it over as a CellJob and receive its CellResponse. They know
// nothing of the solver's internals, so any analyzer (the enriched-RKPM solver, or a closed-form bar
// in the tests) plugs in.
//
// Wiring (micro_main.cpp), e.g.:
//   const CellAnalyzerFactory factory = [](const Config& analysis, double curve_end_strain) {
//     const FractureOptions options = read_fracture_options(analysis, curve_end_strain);  // exit 2 on bad keys
//     return CellAnalyzer([options](const CellJob& job, const StateObserver& observe) {
//       return analyze_cell(*job.mesh, job.cell->geometry, options, observe);
//     });
//   };
//   run_cell_command(config_path, overrides, out, factory);
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "cell_generator.hpp"
#include "cell_mesh.hpp"
#include "cell_response.hpp"
#include "cell_settings.hpp"
#include "uhpc/config.hpp"

namespace uhpc::micro {

// One cell to analyse. Everything is ready: the cell is generated and meshed (meshing is not
// thread-safe, so the drivers do it serially), the output directory exists.
struct CellJob {
  double size_m = 0.0;
  std::size_t size_index = 0;       // 0 for `run`
  std::size_t realization = 0;      // 0 for `run`
  std::uint64_t seed = 0;           // the cell's RNG seed (derive_cell_seed in the ensemble)
  std::filesystem::path out_dir;    // where the driver writes curves.h5 and summary.json; an analyzer
                                    // may put its own files (diagnostics, fields) here too
  CellSettings settings;            // cell, mesh and picture options, microstructure file (Table 2 matrix)
  std::string cell_config;          // the cell config file as resolved
  std::shared_ptr<const GeneratedCell> cell;
  std::shared_ptr<const CellDiscretization> mesh;  // nullptr when discretization.mesh = false
  nlohmann::json analysis;          // the config's "analysis" section with --set applied, unparsed
  double curve_end_strain = 0.0;    // the strain the path must reach: the strain grid's end
  std::string analysis_source;      // the config file, for messages about analysis keys
};

// Called by the analyzer after every converged (accepted) state, in order; index 0 is the unloaded
// cell. Lets the driver report progress; it must be cheap and must not throw.
using StateObserver = std::function<void(std::size_t index, const CellState& state)>;

// Analyses one cell. Returns the load path; a numerical failure is either thrown (NumericalError or
// any std::exception: the driver records the message) or returned as status Failed with a diagnostic
// and the states reached so far. Must be callable from several threads at once (one job each).
using CellAnalyzer = std::function<CellResponse(const CellJob& job, const StateObserver& observe)>;

// Builds the analyzer once per command, before any cell is generated, from the config's "analysis"
// section and the strain its paths must reach (the strain grid's end, strain_grid.max_strain: one
// key for both, so a path can never stop short of the grid; an analyzer with its own stopping
// strain must reject one below it). Read every key through the typed getters there: a bad value
// throws InputError (exit 2) naming the file and 'analysis.<key>', and keys left unread are
// reported as unknown by the driver's finish() afterwards. The same section reaches each job
// unparsed (CellJob::analysis, CellJob::curve_end_strain).
using CellAnalyzerFactory = std::function<CellAnalyzer(const Config& analysis, double curve_end_strain)>;

}  // namespace uhpc::micro
