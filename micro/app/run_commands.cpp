#include "run_commands.hpp"

#include <chrono>
#include <cstdio>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cell_results.hpp"
#include "cell_settings.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/output_lock.hpp"
#include "uhpc/progress.hpp"

namespace fs = std::filesystem;

namespace uhpc::micro {

int run_cell_command(const std::string& config_path, const std::vector<std::string>& overrides_in,
                     const fs::path& out, const CellAnalyzerFactory& factory) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> overrides = overrides_in;
  const std::vector<std::string> cli_cell_overrides = take_cell_overrides(overrides);
  const Config cfg = Config::load(config_path, overrides);
  cfg.accept_any("notes");
  const std::vector<std::string> cell_overrides = config_cell_overrides(cfg, cli_cell_overrides);
  std::string cell_config = cfg.text("cell_config");
  if (fs::path(cell_config).is_relative()) cell_config = (fs::path(cfg.source()).parent_path() / cell_config).string();
  const PostOptions post = read_post_options(cfg);
  const Config analysis = cfg.section("analysis");
  const CellAnalyzer analyzer = factory(analysis, post.grid_max_strain);  // reads (validates) its keys
  cfg.finish();
  const CellSettings settings = load_cell_settings(cell_config, cell_overrides);

  CellJob job;
  job.size_m = settings.cell.side_m;
  job.seed = settings.seed;
  job.out_dir = out;
  job.settings = settings;
  job.cell_config = cell_config;
  job.analysis = analysis.json();
  job.curve_end_strain = post.grid_max_strain;
  job.analysis_source = cfg.source();
  const OutputLock lock = lock_output_directory(out, "uhpc-micro run");
  try {
    prepare_cell(job, "uhpc-micro run");
  } catch (const CellGenerationError& e) {
    rethrow_as_input_error(e, settings, cell_config);
  }

  ProgressOptions po;
  po.unit = "states";
  Progress progress("states", 0, po);
  CellResponse response = run_analyzer(analyzer, job, [&progress](std::size_t, const CellState&) { progress.advance(); });
  progress.finish();
  const CellResult r = post_process(std::move(response), post);
  write_cell_results(out, job, r, post, "uhpc-micro run");

  const CellResponse& resp = r.response;
  std::printf("cell %.2f mm, seed %llu: %s after %zu states, %zu nodes, %zu DOFs\n", job.size_m * 1e3,
              static_cast<unsigned long long>(job.seed), to_string(resp.status),
              resp.states.empty() ? std::size_t{0} : resp.states.size() - 1, resp.nodes, resp.dofs);
  if (r.bridged) {
    const CurveFeatures& f = r.features;
    std::printf("E0_bar = %.1f MPa, peak stress %.3f MPa at e = %.4g, e(d=0.5) = %s, dissipated %.4g J/m^3; "
                "max |d_energy - d_force| = %.2e%s\n",
                resp.E0_bar_Pa * 1e-6, f.peak_stress_Pa * 1e-6, f.strain_at_peak,
                f.strain_at_half_damage ? fmt::format("{:.4g}", *f.strain_at_half_damage).c_str() : "not reached",
                f.dissipated_per_area_J_m3, r.path.max_abs_difference,
                r.path.max_abs_difference > post.bridging_tolerance ? " (above the tolerance)" : "");
  }
  std::printf("operator energy vs stored energy: %.2e of the largest work\n", resp.operator_energy_mismatch);
  spdlog::info("wrote {} and {} in {:.2f} s", (out / "curves.h5").string(), (out / "summary.json").string(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  if (resp.status == CellStatus::Failed)
    throw NumericalError(fmt::format("cell {:.2f} mm, seed {}: {} (details in {})", job.size_m * 1e3, job.seed,
                                     resp.diagnostic, (out / "summary.json").string()));
  return kExitOk;
}

}  // namespace uhpc::micro
