// `uhpc-micro ensemble`: sizes x realizations of analysed cells, their per-size statistics, ensemble.h5.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cell_results.hpp"
#include "cell_settings.hpp"
#include "ensemble_curves.hpp"
#include "run_commands.hpp"
#include "size_dirs.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/ensemble_file.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/hash.hpp"
#include "uhpc/output_lock.hpp"
#include "uhpc/progress.hpp"
#include "uhpc/resources.hpp"

namespace fs = std::filesystem;

namespace uhpc::micro {

namespace {

struct AnalysisEnsembleSettings {
  std::string cell_config;
  std::vector<double> sizes_m;
  std::size_t realizations = 0;
  std::uint64_t base_seed = 0;
  bool retry_failed = true;
  double max_operator_mismatch = 0.05;  // cells above it are suspect: excluded from the mean, listed
  PostOptions post;
};

// [choice] A cell's expected cost, for the progress line's percentage and ETA only: the fourth power of
// its side. The shipped ensemble's mean cell times at 100 um, 28 / 129 / 241 / 580 s for 3.0 / 4.5 / 5.0 /
// 6.5 mm, grow as side^3.9; counting cells instead put the ETA of a resumed run, 6.5 mm cells first, 3x
// too late.
double expected_cell_work(double size_m) { return std::pow(size_m * 1e3, 4); }

AnalysisEnsembleSettings read_settings(const Config& cfg) {
  AnalysisEnsembleSettings e;
  cfg.accept_any("notes");
  e.cell_config = cfg.text("cell_config");
  if (fs::path(e.cell_config).is_relative())
    e.cell_config = (fs::path(cfg.source()).parent_path() / e.cell_config).string();
  e.sizes_m = cfg.numbers("cell_sizes_m", Range::positive());
  // The ensemble file needs strictly ascending sizes, and each size its own directory.
  for (std::size_t i = 1; i < e.sizes_m.size(); ++i) {
    if (!(e.sizes_m[i] > e.sizes_m[i - 1]))
      cfg.fail("cell_sizes_m", fmt::format("must be strictly ascending, but entry {} ({}) follows {}", i,
                                           e.sizes_m[i], e.sizes_m[i - 1]));
  }
  require_distinct_size_dirs(cfg, "cell_sizes_m", e.sizes_m);
  e.realizations = static_cast<std::size_t>(cfg.integer("realizations", Range::closed(1, 10000)));
  e.base_seed = static_cast<std::uint64_t>(cfg.integer("base_seed", Range::closed(0, 9007199254740991.0)));
  e.retry_failed = cfg.flag("retry_failed");
  e.max_operator_mismatch = cfg.number("max_operator_mismatch", Range::positive());
  e.post = read_post_options(cfg);
  return e;
}

struct CellOutcome {
  CellJob job;
  CellResult result;
};

nlohmann::json spread_json(const std::vector<double>& v) {
  if (v.empty()) return {{"mean", nullptr}, {"std", nullptr}, {"min", nullptr}, {"max", nullptr}, {"count", 0}};
  const Spread s = spread(v);
  return {{"mean", s.mean},
          {"std", s.std},
          {"min", *std::min_element(v.begin(), v.end())},
          {"max", *std::max_element(v.begin(), v.end())},
          {"count", s.count}};
}

// A cell counts in the mean when it finished (not Failed) and its curve covers the whole grid
// (separated, or stopped beyond the grid's end): an incomplete curve would bias the mean.
bool averaged(const CellResult& r) { return r.response.status != CellStatus::Failed && r.bridged && r.resampled.complete; }

// The cells (index size * realizations + realization) a run handles: every cell, or the selection's.
// Bad input when the selection names a size or a realization the ensemble does not have.
std::vector<std::size_t> selected_cells(const AnalysisEnsembleSettings& e, const EnsembleSelection& sel) {
  if (sel.assemble_only && (sel.only_size_mm || sel.only_cell))
    throw InputError("--assemble-only: cannot be combined with --only-size or --only-cell");
  std::optional<std::size_t> size_index;
  if (sel.only_size_mm) {
    const double mm = *sel.only_size_mm;
    std::string sizes;
    for (std::size_t i = 0; i < e.sizes_m.size(); ++i) {
      sizes += fmt::format("{}{:g}", i ? ", " : "", e.sizes_m[i] * 1e3);
      if (std::abs(e.sizes_m[i] * 1e3 - mm) <= 1e-9 * e.sizes_m[i] * 1e3) size_index = i;
    }
    if (!size_index)
      throw InputError(fmt::format("--only-size {:g}: not one of the ensemble's cell sizes ({} mm)", mm, sizes));
  }
  if (sel.only_cell && (*sel.only_cell < 0 || *sel.only_cell >= static_cast<long long>(e.realizations)))
    throw InputError(fmt::format("--only-cell {}: out of range, the ensemble's realizations are 0 to {}", *sel.only_cell,
                                 e.realizations - 1));
  std::vector<std::size_t> cells;
  for (std::size_t i = 0; i < e.sizes_m.size(); ++i)
    for (std::size_t r = 0; r < e.realizations; ++r)
      if ((!size_index || *size_index == i) && (!sel.only_cell || static_cast<long long>(r) == *sel.only_cell))
        cells.push_back(i * e.realizations + r);
  return cells;
}

// --select FILE (run_commands.hpp): per size, the realizations drawn, with multiplicities.
struct CellDraws {
  std::vector<std::vector<std::size_t>> per_size;  // realization indices, in the file's order
  std::string file;
  std::string hash;  // of the draws alone (notes do not count), mixed into the ensemble's config hash
};

constexpr const char* kCellSelectionFormat = "uhpc-cell-selection/1";

CellDraws read_cell_selection(const fs::path& file, const AnalysisEnsembleSettings& e) {
  CellDraws d;
  d.file = file.string();
  const Config cfg = Config::load(d.file);
  const std::string format = cfg.text("format");
  if (format != kCellSelectionFormat)
    cfg.fail("format", fmt::format("expected \"{}\", got \"{}\"", kCellSelectionFormat, format));
  cfg.accept_any("notes");
  const std::vector<Config> sizes = cfg.sections("sizes");
  std::string listed;
  for (std::size_t i = 0; i < e.sizes_m.size(); ++i) listed += fmt::format("{}{:g}", i ? ", " : "", e.sizes_m[i] * 1e3);
  if (sizes.size() != e.sizes_m.size())
    cfg.fail("sizes", fmt::format("has {} entries, the ensemble {} sizes ({} mm): one entry per size, in order",
                                  sizes.size(), e.sizes_m.size(), listed));
  nlohmann::json canonical = nlohmann::json::array();
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const double size_m = sizes[i].number("cell_size_m", Range::positive());
    if (std::abs(size_m - e.sizes_m[i]) > 1e-9 * e.sizes_m[i])
      sizes[i].fail("cell_size_m", fmt::format("{:g} m is not the ensemble's size {} ({:g} m; sizes {} mm, in order)",
                                               size_m, i, e.sizes_m[i], listed));
    const std::vector<double> drawn =
        sizes[i].numbers("realizations", Range::closed(0.0, static_cast<double>(e.realizations - 1)));
    std::vector<std::size_t> r;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
      if (drawn[k] != std::floor(drawn[k]))
        sizes[i].fail("realizations", fmt::format("entry {} ({:g}) is not an integer", k, drawn[k]));
      r.push_back(static_cast<std::size_t>(drawn[k]));
    }
    canonical.push_back({{"cell_size_m", e.sizes_m[i]}, {"realizations", r}});
    d.per_size.push_back(std::move(r));
  }
  cfg.finish();
  d.hash = fnv1a64_hex(canonical.dump());
  return d;
}

// The combinations of --select and --assemble-to that make sense (bad input otherwise).
void check_assemble_options(const EnsembleSelection& sel, const fs::path& out) {
  if (sel.cell_selection && !sel.assemble_only)
    throw InputError("--select: needs --assemble-only (a selection assembles finished cells, it analyses none)");
  if (sel.cell_selection && !sel.assemble_to)
    throw InputError("--select: needs --assemble-to DIR (a resampled ensemble must not replace " +
                     (out / "ensemble.h5").string() + ")");
  if (sel.assemble_to && !sel.assemble_only) throw InputError("--assemble-to: needs --assemble-only");
  if (sel.assemble_to && sel.cell_selection && fs::weakly_canonical(*sel.assemble_to) == fs::weakly_canonical(out))
    throw InputError("--assemble-to " + sel.assemble_to->string() +
                     ": is the cells' directory --out; a resampled ensemble must not replace its ensemble.h5");
}

// Everything a run reads before it analyses anything (bad input fails here, at once).
struct EnsembleInputs {
  AnalysisEnsembleSettings e;
  std::vector<CellSettings> per_size;  // the cell settings of each size (validated)
  std::string post_hash;
  nlohmann::json analysis;  // a copy: the Config is not read from the workers
  std::string source;
  std::string config_hash;
  CellAnalyzer analyzer;
};

EnsembleInputs read_inputs(const std::string& config_path, const std::vector<std::string>& overrides_in,
                           const CellAnalyzerFactory& factory) {
  EnsembleInputs in;
  std::vector<std::string> overrides = overrides_in;
  const std::vector<std::string> cli_cell_overrides = take_cell_overrides(overrides);
  const Config cfg = Config::load(config_path, overrides);
  in.e = read_settings(cfg);
  const std::vector<std::string> cell_overrides = config_cell_overrides(cfg, cli_cell_overrides);
  const Config analysis = cfg.section("analysis");
  in.analyzer = factory(analysis, in.e.post.grid_max_strain);
  cfg.finish();
  for (double size : in.e.sizes_m) in.per_size.push_back(load_cell_settings(in.e.cell_config, cell_overrides, size));
  in.post_hash = post_options_hash(in.e.post);
  in.analysis = analysis.json();
  in.source = cfg.source();
  in.config_hash = cfg.hash();
  return in;
}

// Cell k's job (k = size index x realizations + realization).
CellJob cell_job(const EnsembleInputs& in, const fs::path& out, std::size_t k) {
  const AnalysisEnsembleSettings& e = in.e;
  const std::size_t i = k / e.realizations, r = k % e.realizations;
  CellJob job;
  job.size_m = e.sizes_m[i];
  job.size_index = i;
  job.realization = r;
  job.seed = derive_cell_seed(e.base_seed, i, r);
  job.out_dir = out / size_label(job.size_m) / fmt::format("cell_{:02d}", r);
  job.settings = in.per_size[i];
  job.settings.seed = job.seed;
  job.cell_config = e.cell_config;
  job.analysis = in.analysis;
  job.curve_end_strain = e.post.grid_max_strain;
  job.analysis_source = in.source;
  return job;
}

// Reloads a finished run of the cell when one of the same cell and analysis is on disk (a failed one
// only when it is not to be retried); true when it did.
bool reload_cell(const EnsembleInputs& in, const EnsembleSelection& selection, CellOutcome& o) {
  if (!fs::is_directory(o.job.out_dir)) return false;
  // Read (and refreshed) by this run alone: a cell another run is analysing stops this one, exit 2.
  const OutputLock lock = lock_output_directory(o.job.out_dir, "uhpc-micro ensemble");
  std::optional<StoredCell> stored =
      load_cell_results(o.job.out_dir, cell_hash(o.job), in.post_hash, former_cell_hash(o.job));
  if (!stored || (stored->response.status == CellStatus::Failed && in.e.retry_failed && !selection.assemble_only))
    return false;
  o.result = post_process(std::move(stored->response), in.e.post);
  o.result.reloaded = true;
  // Post-processing options changed since, or the cell was stamped with the former hash (notes included):
  // write its files again, derived data and hash of today.
  if (!stored->post_hash_matches || stored->former_hash)
    write_cell_results(o.job.out_dir, o.job, o.result, in.e.post, "uhpc-micro ensemble");
  return true;
}

// Generates, meshes and analyses one cell and writes its results (a cell that cannot be generated is a
// failed cell, not a failed run).
void analyse_cell(const EnsembleInputs& in, CellOutcome& o) {
  CellJob& job = o.job;
  // Each cell is locked while it is analysed and written, so the runs of a part of the ensemble
  // (--only-size, --only-cell: one batch job each) share the directory but never a cell.
  const OutputLock lock = lock_output_directory(job.out_dir, "uhpc-micro ensemble");
  CellResponse response;
  try {
    prepare_cell(job, "uhpc-micro ensemble");
    response = run_analyzer(in.analyzer, job, [](std::size_t, const CellState&) {});
  } catch (const CellGenerationError& err) {
    response.side_m = job.size_m;
    response.status = CellStatus::Failed;
    response.diagnostic = std::string("cell generation failed: ") + err.what();
  }
  job.cell.reset();  // the geometry and the mesh are not needed any more: free them
  job.mesh.reset();
  o.result = post_process(std::move(response), in.e.post);
  write_cell_results(job.out_dir, job, o.result, in.e.post, "uhpc-micro ensemble");
  if (o.result.response.status == CellStatus::Failed)
    spdlog::warn("cell {} (size {:.2f} mm, seed {}) failed: {}", job.out_dir.string(), job.size_m * 1e3, job.seed,
                 o.result.response.diagnostic);
}

// Runs `analyse` on the chosen cells that were not reloaded, on `jobs` threads (0: one per hardware
// thread), largest cells first. The first exception (bad input, or a file that cannot be written) stops
// the run and is rethrown; finished cells stay on disk.
void analyse_cells(const std::vector<std::size_t>& chosen, std::vector<CellOutcome>& outcomes, int jobs,
                   Progress& progress, const std::function<void(CellOutcome&)>& analyse) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex error_mutex;
  std::exception_ptr error;
  std::size_t threads = jobs > 0 ? static_cast<std::size_t>(jobs) : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min(threads, chosen.size());
  const auto worker = [&] {
#ifdef _OPENMP
    // [choice] With several cells at once each solve runs serially (its OpenMP loops get one thread in
    // this worker), so -j N uses N cores without oversubscription; with -j 1 the solve keeps them all.
    if (threads > 1) omp_set_num_threads(1);
#endif
    while (!stop.load()) {
      const std::size_t taken = next.fetch_add(1);
      if (taken >= chosen.size()) break;
      // Largest cells first (sizes are ascending): the longest solves start first and the workers
      // finish together instead of one of them ending the run alone on a 6.5 mm cell.
      CellOutcome& o = outcomes[chosen[chosen.size() - 1 - taken]];
      if (o.result.reloaded) continue;
      try {
        analyse(o);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
      progress.advance(1, expected_cell_work(o.job.size_m));
    }
  };
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

// One size's cells: which count in the mean, their averaged curve and their statistics.
struct SizeSummary {
  SizeCurves curves;
  nlohmann::json json;
  std::size_t ok = 0, failed = 0, incomplete = 0, suspect = 0, reloaded = 0;
};

// `draws`: the realizations averaged, each as often as listed (every realization once for the ensemble).
SizeSummary summarize_size(const AnalysisEnsembleSettings& e, const std::vector<CellOutcome>& outcomes, std::size_t i,
                           const std::vector<std::size_t>& draws, const fs::path& out) {
  SizeSummary z;
  std::vector<const ResampledCurve*> used;
  std::vector<double> peaks, e50, E0, dissipated, walls;
  double bridging_max = 0.0;
  nlohmann::json failures = nlohmann::json::array(), suspects = nlohmann::json::array(), seeds = nlohmann::json::array();
  for (std::size_t r : draws) {
    const CellOutcome& o = outcomes[i * e.realizations + r];
    const CellResult& res = o.result;
    seeds.push_back(o.job.seed);
    if (res.response.wall_s > 0.0) walls.push_back(res.response.wall_s);  // as measured when it ran
    if (res.reloaded) ++z.reloaded;
    if (res.response.status == CellStatus::Failed) {
      ++z.failed;
      failures.push_back({{"realization", r},
                          {"seed", o.job.seed},
                          {"directory", fs::relative(o.job.out_dir, out).string()},
                          {"diagnostic", res.response.diagnostic}});
      continue;
    }
    // A discrete operator whose energy parts from the stored energy has a spurious soft mode
    // (CellResponse::operator_energy_mismatch): such a path is not evidence, whatever its status.
    if (res.response.operator_energy_mismatch > e.max_operator_mismatch) {
      ++z.suspect;
      suspects.push_back({{"realization", r},
                          {"seed", o.job.seed},
                          {"directory", fs::relative(o.job.out_dir, out).string()},
                          {"status", to_string(res.response.status)},
                          {"operator_energy_mismatch", res.response.operator_energy_mismatch}});
      continue;
    }
    if (!averaged(res)) {
      ++z.incomplete;
      continue;
    }
    used.push_back(&res.resampled);
    peaks.push_back(res.features.peak_stress_Pa);
    if (res.features.strain_at_half_damage) e50.push_back(*res.features.strain_at_half_damage);
    E0.push_back(res.response.E0_bar_Pa);
    dissipated.push_back(res.features.dissipated_per_area_J_m3);
    bridging_max = std::max(bridging_max, res.path.max_abs_difference);
  }
  z.curves = size_curves(e.sizes_m[i], e.post.grid, used);
  z.ok = draws.size() - z.failed;
  const auto or_null = [&](double v) { return used.empty() ? nlohmann::json(nullptr) : nlohmann::json(v); };
  z.json = {{"cell_size_m", e.sizes_m[i]},
            {"directory", size_label(e.sizes_m[i])},
            {"cells", draws.size()},
            {"cells_ok", z.ok},
            {"cells_failed", z.failed},
            {"cells_incomplete", z.incomplete},
            {"cells_suspect", z.suspect},
            {"cells_averaged", used.size()},
            {"cells_reloaded", z.reloaded},
            {"nominal_strength_Pa", or_null(z.curves.nominal_strength_Pa)},
            {"strain_at_nominal_strength", or_null(z.curves.strain_at_nominal_strength)},
            {"peak_stress_Pa", spread_json(peaks)},
            {"strain_at_half_damage", spread_json(e50)},
            {"E0_bar_Pa", spread_json(E0)},
            {"dissipated_energy_density_J_m3", spread_json(dissipated)},
            {"bridging_max_abs_difference", bridging_max},
            {"cell_wall_s", spread_json(walls)},
            {"seeds", seeds},
            {"failures", failures},
            {"suspects", suspects}};
  const Spread sp = spread(peaks), se = spread(e50);
  std::printf("%8.2f %6zu %6zu %10zu %8zu %8zu %18.3f %12.3f +- %7.3f %20.4g\n", e.sizes_m[i] * 1e3, draws.size(),
              z.failed, z.incomplete, z.suspect, used.size(), z.curves.nominal_strength_Pa * 1e-6, sp.mean * 1e-6,
              sp.std * 1e-6, se.count ? se.mean : std::numeric_limits<double>::quiet_NaN());
  return z;
}

}  // namespace

int run_ensemble_command(const std::string& config_path, const std::vector<std::string>& overrides,
                         const fs::path& out, int jobs, const CellAnalyzerFactory& factory,
                         const EnsembleSelection& selection) {
  const auto t0 = std::chrono::steady_clock::now();
  const EnsembleInputs in = read_inputs(config_path, overrides, factory);
  const AnalysisEnsembleSettings& e = in.e;
  check_assemble_options(selection, out);
  // The realizations averaged per size: each once, or a --select file's draws (with multiplicities).
  std::optional<CellDraws> draws;
  if (selection.cell_selection) draws = read_cell_selection(*selection.cell_selection, e);
  std::vector<std::vector<std::size_t>> per_size_draws(e.sizes_m.size());
  for (std::size_t i = 0; i < e.sizes_m.size(); ++i) {
    if (draws) {
      per_size_draws[i] = draws->per_size[i];
    } else {
      for (std::size_t r = 0; r < e.realizations; ++r) per_size_draws[i].push_back(r);
    }
  }
  // A partial run (--only-size, --only-cell) handles its cells alone and writes no ensemble file.
  std::vector<std::size_t> chosen = selected_cells(e, selection);
  if (draws) {  // only the cells drawn are reloaded (each once)
    chosen.clear();
    for (std::size_t i = 0; i < e.sizes_m.size(); ++i)
      for (std::size_t r : per_size_draws[i]) chosen.push_back(i * e.realizations + r);
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  }
  std::size_t total = 0;
  for (const auto& d : per_size_draws) total += d.size();
  const bool partial = selection.only_size_mm.has_value() || selection.only_cell.has_value();
  // Where ensemble.h5 and summary.json go: the cells' directory, or --assemble-to's.
  const fs::path dest = selection.assemble_to.value_or(out);
  // A run over every cell (or --assemble-only) writes ensemble.h5 and summary.json: one such run at a time.
  // Runs of a part lock only their cells (below), so that batch jobs of one ensemble run side by side.
  OutputLock ensemble_lock;
  if (!partial) ensemble_lock = lock_output_directory(dest, "uhpc-micro ensemble");

  // Every finished cell is reloaded before any solve starts, so the progress count and its ETA are the
  // solves' from the first line (the solves go largest first, and a resumed run's finished cells are
  // often the first realizations of every size).
  std::vector<CellOutcome> outcomes(e.sizes_m.size() * e.realizations);
  std::size_t reloaded_cells = 0;
  double reloaded_work = 0, total_work = 0;
  std::vector<std::string> unfinished;
  for (std::size_t k : chosen) {
    CellOutcome& o = outcomes[k];
    o.job = cell_job(in, out, k);
    total_work += expected_cell_work(o.job.size_m);
    if (reload_cell(in, selection, o)) {
      ++reloaded_cells;
      reloaded_work += expected_cell_work(o.job.size_m);
    } else {
      unfinished.push_back(fs::relative(o.job.out_dir, out).string());
    }
  }
  // --assemble-only analyses nothing: the cells must all be there, finished with this configuration.
  if (selection.assemble_only && !unfinished.empty()) {
    std::string list;
    for (std::size_t n = 0; n < unfinished.size() && n < 5; ++n) list += (n ? ", " : "") + unfinished[n];
    if (unfinished.size() > 5) list += ", ...";
    throw InputError(fmt::format("--assemble-only: {} of {} cells in {} are not finished with this configuration ({}): "
                                 "run them first (--only-cell, --only-size, or without --assemble-only)",
                                 unfinished.size(), chosen.size(), out.string(), list));
  }
  ProgressOptions po;
  po.unit = "cells";
  Progress progress("cells", chosen.size(), po);
  progress.set_work_total(total_work);
  if (reloaded_cells > 0) {
    spdlog::info("{} of {} cells reloaded from {}", reloaded_cells, chosen.size(), out.string());
    progress.skip(reloaded_cells, reloaded_work);
  }
  analyse_cells(chosen, outcomes, jobs, progress, [&](CellOutcome& o) { analyse_cell(in, o); });
  progress.finish();
  const auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };

  if (partial) {
    std::size_t failed = 0;
    for (std::size_t k : chosen)
      if (outcomes[k].result.response.status == CellStatus::Failed) ++failed;
    std::printf("%zu of %zu cells selected (%zu reloaded), %zu failed, in %.1f s; ensemble.h5 and summary.json are "
                "written by a run over every cell (e.g. --assemble-only once all are finished)\n",
                chosen.size(), e.sizes_m.size() * e.realizations, reloaded_cells, failed, wall());
    return kExitOk;
  }

  // Per-size statistics, the ensemble file and the summary.
  std::vector<SizeCurves> curves;
  nlohmann::json sizes = nlohmann::json::array();
  std::size_t ok_total = 0, failed_total = 0, incomplete_total = 0, suspect_total = 0, reloaded_total = 0;
  std::printf("%8s %6s %6s %10s %8s %8s %18s %22s %20s\n", "size_mm", "cells", "failed", "incomplete", "suspect",
              "averaged", "nominal_MPa", "peak_MPa mean +- std", "e(d=0.5) mean");
  for (std::size_t i = 0; i < e.sizes_m.size(); ++i) {
    SizeSummary z = summarize_size(e, outcomes, i, per_size_draws[i], out);
    curves.push_back(std::move(z.curves));
    sizes.push_back(std::move(z.json));
    ok_total += z.ok;
    failed_total += z.failed;
    incomplete_total += z.incomplete;
    suspect_total += z.suspect;
    reloaded_total += z.reloaded;
  }
  std::vector<double> skipped;
  const Ensemble ensemble = to_ensemble(e.post.grid, curves, &skipped);
  const Provenance provenance = Provenance::make(
      "uhpc-micro ensemble", fnv1a64_hex(in.config_hash + in.per_size.front().config_hash + (draws ? draws->hash : "")),
      e.base_seed);
  if (ensemble.size_count() > 0) write_ensemble(dest / "ensemble.h5", ensemble, provenance);
  nlohmann::json selection_json = nullptr;
  if (draws) {
    selection_json = {{"file", draws->file}, {"hash", draws->hash}, {"cells_directory", out.string()}, {"sizes", {}}};
    for (std::size_t i = 0; i < e.sizes_m.size(); ++i)
      selection_json["sizes"].push_back({{"cell_size_m", e.sizes_m[i]}, {"realizations", per_size_draws[i]}});
  }
  const double wall_s = wall();
  const nlohmann::json summary = {
      {"format", "uhpc-micro-ensemble/1"},
      {"base_seed", e.base_seed},
      {"realizations", e.realizations},
      {"seed_rule", "derive_cell_seed(base_seed, size_index, realization): SplitMix64 chain, 53 bits"},
      {"cells", total},
      {"cell_selection", selection_json},
      {"cells_ok", ok_total},
      {"cells_failed", failed_total},
      {"cells_incomplete", incomplete_total},
      {"cells_suspect", suspect_total},
      {"cells_reloaded", reloaded_total},
      {"averaging_rule", "cells not failed, not suspect (operator_energy_mismatch above max_operator_mismatch) and "
                         "whose curve covers the whole strain grid; the others are excluded and listed"},
      {"max_operator_mismatch", e.max_operator_mismatch},
      {"ensemble_file", ensemble.size_count() > 0 ? nlohmann::json("ensemble.h5") : nlohmann::json(nullptr)},
      {"sizes_without_cells_m", skipped},
      {"post_options", post_options_json(e.post)},
      {"sizes", sizes},
      {"wall_s", wall_s},
      {"peak_memory_MiB", peak_memory_MiB()},
      {"provenance", provenance.to_json()}};
  write_text_atomic(dest / "summary.json", summary.dump(2) + "\n");
  std::printf("%zu cells (%zu reloaded), %zu failed, %zu incomplete, %zu suspect, in %.1f s\n", total, reloaded_total,
              failed_total, incomplete_total, suspect_total, wall_s);
  if (failed_total > 0) spdlog::warn("{} cells failed: see {}", failed_total, (dest / "summary.json").string());
  if (!skipped.empty())
    throw NumericalError(fmt::format("{} of {} sizes have no cell to average ({}); see {}", skipped.size(),
                                     e.sizes_m.size(),
                                     ensemble.size_count() > 0 ? "ensemble.h5 holds the others" : "no ensemble.h5 written",
                                     (dest / "summary.json").string()));
  spdlog::info("wrote {} and {}", (dest / "ensemble.h5").string(), (dest / "summary.json").string());
  return kExitOk;
}

}  // namespace uhpc::micro
