#pragma once
// One analysed cell's results: the post-processing of its CellResponse (energy bridging, the
// strain-controlled curve, the common grid) and its files, DIR/curves.h5 and DIR/summary.json,
// written atomically and read back for resuming an ensemble. Shared by `run` and `ensemble`.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cell_analyzer.hpp"
#include "energy_bridging.hpp"
#include "uhpc/config.hpp"
#include "uhpc/provenance.hpp"

namespace uhpc::micro {

inline constexpr const char* kCellSummaryFormat = "uhpc-micro-run/2";

// The post-processing options both commands read (keys "bridging" and "strain_grid").
struct PostOptions {
  BridgingOptions bridging;
  double bridging_tolerance = 0.01;  // |d_energy - d_force| above it is flagged (the 1 %)
  std::vector<double> grid;          // common strain grid
  double grid_max_strain = 0.0;
  std::size_t grid_points = 0;
};

// Reads "bridging.{strain_control, damage_measure, tolerance}" and "strain_grid.{max_strain, points}".
PostOptions read_post_options(const Config& cfg);
nlohmann::json post_options_json(const PostOptions& o);
// Identifies the post-processing settings (a resumed cell is re-post-processed when it changes).
std::string post_options_hash(const PostOptions& o);

struct CellResult {
  CellResponse response;
  bool bridged = false;              // false when the response cannot be bridged (a failed cell)
  std::string bridging_error;        // why not
  BridgedPath path;
  ControlledCurve curve;
  ResampledCurve resampled;
  CurveFeatures features;
  bool reloaded = false;             // taken from a previous run's files
};

// Never throws for a Failed response: what cannot be bridged is recorded in bridging_error (and a
// bridging error turns an otherwise good response into Failed, with that diagnostic).
CellResult post_process(CellResponse response, const PostOptions& options);

// Generates the cell of `job` (job.settings with job.seed) and meshes it when the settings ask for a
// mesh, filling job.cell and job.mesh, and writes job.out_dir/cell.json. gmsh is one global state, so
// meshing holds a process-wide mutex (the analyses themselves run in parallel). Throws
// CellGenerationError when the cell cannot be generated.
void prepare_cell(CellJob& job, const std::string& program);

// Runs the analyzer on a prepared job and times it. An InputError propagates (bad input stops the
// command); any other exception becomes a Failed response carrying the message, so one cell's failure
// never stops an ensemble. A Failed response without a diagnostic gets one.
CellResponse run_analyzer(const CellAnalyzer& analyzer, const CellJob& job, const StateObserver& observe);

// The revision of the fracture solver's results. Bump it with every change of the solver or of its
// defaults that changes a cell's result under the same configuration: it enters cell_hash, so a
// resumed ensemble recomputes such cells instead of reloading results of another solver.
// 2: quadrature.cracked_correction = none by default (was VCI).
// 3: Newton corrections by GMRES with an earlier factorization (newton.krylov_iterations = 16): the
//    same path to within the Newton tolerance, but not bit for bit.
inline constexpr int kFractureSolverRevision = 3;

// What identifies a cell's solve: the cell settings, size, seed, the analysis section and
// kFractureSolverRevision; the configs' values, not their notes (Config::hash).
std::string cell_hash(const CellJob& job);
// The same in the scheme before 2026-12-06, which hashed the notes too: a cell recorded under it is
// still reloaded, and re-stamped with cell_hash.
std::string former_cell_hash(const CellJob& job);

// Writes DIR/curves.h5 then DIR/summary.json (each atomically; summary.json last, so its presence
// means the cell is finished). `program` goes into the provenance.
void write_cell_results(const std::filesystem::path& dir, const CellJob& job, const CellResult& result,
                        const PostOptions& options, const std::string& program);

// The summary.json document (also used by the ensemble's summary).
nlohmann::json cell_summary_json(const CellJob& job, const CellResult& result, const PostOptions& options,
                                 const Provenance& provenance);

// A previous run's response of this cell, when DIR/summary.json exists with this cell_hash (or
// `former_cell_hash`, when given) and DIR/curves.h5 reads back; std::nullopt otherwise (the cell is then
// run again). `post_hash_matches` says whether the files were post-processed with the current options,
// `former_hash` whether they carry the former hash; either way the caller writes them again.
struct StoredCell {
  CellResponse response;
  bool post_hash_matches = false;
  bool former_hash = false;
};
std::optional<StoredCell> load_cell_results(const std::filesystem::path& dir, const std::string& expected_cell_hash,
                                            const std::string& expected_post_hash,
                                            const std::string& former_cell_hash = "");

}  // namespace uhpc::micro
