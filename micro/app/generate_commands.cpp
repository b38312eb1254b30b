#include "generate_commands.hpp"

#include <chrono>
#include <cstdio>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "size_dirs.hpp"
#include "cell_io.hpp"
#include "cell_picture.hpp"
#include "cell_settings.hpp"
#include "elastic_settings.hpp"
#include "ensemble_stats.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/hash.hpp"
#include "uhpc/output_lock.hpp"
#include "uhpc/progress.hpp"
#include "uhpc/provenance.hpp"

namespace fs = std::filesystem;

namespace uhpc::micro {

namespace {

struct CellResult {
  GeneratedCell cell;
  std::optional<CellDiscretization> mesh;
};

GeneratedCell generate_or_explain(const CellSettings& s, const std::string& cell_config_path) {
  try {
    return generate_cell(s.cell, s.seed);
  } catch (const CellGenerationError& e) {
    rethrow_as_input_error(e, s, cell_config_path);
  }
}

// Generates, meshes and writes one cell into `dir`.
CellResult generate_one(const CellSettings& s, const std::string& cell_config_path, const fs::path& dir,
                        const std::string& program, bool picture) {
  CellResult r{generate_or_explain(s, cell_config_path), std::nullopt};
  if (s.mesh_enabled) r.mesh = mesh_cell(r.cell.geometry, s.mesh);
  const CellDiscretization* mesh = r.mesh ? &*r.mesh : nullptr;
  const Provenance provenance = Provenance::make(program, s.config_hash, s.seed);
  write_text_atomic(dir / "cell.json", cell_json(r.cell, s, mesh, provenance).dump(2) + "\n");
  if (picture) {
    PictureOptions pic = s.picture;
    const CellGeometry& g = r.cell.geometry;
    pic.caption = fmt::format("{:.1f} x {:.1f} mm, seed {}, {} pores, porosity {:.2f} %", g.side_m * 1e3,
                              g.side_m * 1e3, s.seed, g.pores.size(), 100.0 * g.porosity());
    if (mesh) pic.caption += fmt::format(", {} nodes", mesh->node_count());
    write_text_atomic(dir / "cell.svg", cell_svg(g, mesh, pic));
  }
  return r;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int run_generate(const std::string& config_path, const std::vector<std::string>& overrides, const fs::path& out) {
  const auto t0 = std::chrono::steady_clock::now();
  const CellSettings s = load_cell_settings(config_path, overrides);
  const OutputLock lock = lock_output_directory(out, "uhpc-micro generate");
  const CellResult r = generate_one(s, config_path, out, "uhpc-micro generate", true);
  const CellGeometry& g = r.cell.geometry;
  std::printf("cell %.2f mm, seed %llu: %zu pores (largest %.1f um), %zu seeds, porosity %.5f (target %g +- %g)\n",
              g.side_m * 1e3, static_cast<unsigned long long>(s.seed), g.pores.size(),
              g.pores.empty() ? 0.0 : g.pores.front().diameter_m * 1e6, g.seeds.size(), g.porosity(),
              s.cell.porosity.target, s.cell.porosity.tolerance);
  if (r.mesh)
    std::printf("discretization: %zu nodes, %zu triangles (nominal spacing %.1f um)\n", r.mesh->node_count(),
                r.mesh->triangle_count(), s.mesh.nominal_spacing_m * 1e6);
  spdlog::info("wrote {} and {} in {:.2f} s", (out / "cell.json").string(), (out / "cell.svg").string(),
               seconds_since(t0));
  return kExitOk;
}

namespace {

struct EnsembleSettings {
  std::string cell_config;
  std::vector<double> sizes_m;
  int realizations = 0;
  std::uint64_t base_seed = 0;
  int histogram_bins = 0;
  bool pictures = true;
};

EnsembleSettings read_ensemble(const Config& cfg) {
  EnsembleSettings e;
  cfg.accept_any("notes");
  e.cell_config = cfg.text("cell_config");
  if (fs::path(e.cell_config).is_relative()) e.cell_config = (fs::path(cfg.source()).parent_path() / e.cell_config).string();
  e.sizes_m = cfg.numbers("cell_sizes_m", Range::positive());
  require_distinct_size_dirs(cfg, "cell_sizes_m", e.sizes_m);
  e.realizations = static_cast<int>(cfg.integer("realizations", Range::closed(1, 10000)));
  e.base_seed = static_cast<std::uint64_t>(cfg.integer("base_seed", Range::closed(0, 9007199254740991.0)));
  e.histogram_bins = static_cast<int>(cfg.integer("histogram_bins", Range::closed(2, 10000)));
  e.pictures = cfg.flag("pictures");
  cfg.finish();
  return e;
}

nlohmann::json spread_json(const Spread& s) {
  return {{"mean", s.mean}, {"min", s.min}, {"max", s.max}, {"stddev", s.stddev}};
}

}  // namespace

int run_generate_ensemble(const std::string& config_path, const std::vector<std::string>& overrides_in,
                          const fs::path& out) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> overrides = overrides_in;
  const std::vector<std::string> cell_overrides = take_cell_overrides(overrides);
  const Config cfg = Config::load(config_path, overrides);
  const EnsembleSettings e = read_ensemble(cfg);

  // Validate every size before generating anything, so bad input fails at once.
  std::vector<CellSettings> per_size;
  for (double size : e.sizes_m) per_size.push_back(load_cell_settings(e.cell_config, cell_overrides, size));
  const OutputLock lock = lock_output_directory(out, "uhpc-micro generate-ensemble");

  ProgressOptions progress_options;
  progress_options.unit = "cells";
  Progress progress("cells", e.sizes_m.size() * static_cast<std::size_t>(e.realizations), progress_options);
  nlohmann::json sizes = nlohmann::json::array();
  std::string csv =
      "# uhpc-micro generate-ensemble: pore-size histogram per cell size (ESD bins over [gamma, truncation])\n"
      "# drawn = every Burr draw (follows the truncated law), placed = pores in the cells (the porosity budget\n"
      "# rejects large draws near the end, so placed pores lean small); densities in 1/m\n"
      "size_m,bin_lo_m,bin_hi_m,drawn_count,placed_count,drawn_density_1_m,placed_density_1_m,burr_density_1_m\n";
  std::printf("%8s %6s %20s %9s %20s %26s %22s\n", "size_mm", "cells", "pores mean [min,max]", "expected",
              "largest_um mean/max", "porosity mean [min,max]", "nodes mean [min,max]");
  for (std::size_t i = 0; i < e.sizes_m.size(); ++i) {
    CellSettings s = per_size[i];
    const BurrXII burr(s.cell.burr, s.cell.truncation_m);
    std::vector<GeneratedCell> cells;
    std::vector<CellDiscretization> meshes;
    nlohmann::json seeds = nlohmann::json::array();
    for (int r = 0; r < e.realizations; ++r) {
      s.seed = derive_cell_seed(e.base_seed, i, static_cast<std::uint64_t>(r));
      seeds.push_back(s.seed);
      const fs::path dir = out / size_label(e.sizes_m[i]) / fmt::format("cell_{:02d}", r);
      CellResult result = generate_one(s, e.cell_config, dir, "uhpc-micro generate-ensemble", e.pictures);
      cells.push_back(std::move(result.cell));
      if (result.mesh) meshes.push_back(std::move(*result.mesh));
      progress.advance();
    }
    const SizeStatistics st = size_statistics(cells, meshes, burr, s.cell.porosity.target, e.histogram_bins);
    sizes.push_back({{"cell_size_m", st.side_m},
                     {"directory", size_label(st.side_m)},
                     {"cells", st.cells},
                     {"seeds", seeds},
                     {"pore_count", spread_json(st.pore_count)},
                     {"expected_pore_count", st.expected_pore_count},
                     {"largest_pore_diameter_m", spread_json(st.largest_pore_m)},
                     {"porosity", spread_json(st.porosity)},
                     {"node_count", meshes.empty() ? nlohmann::json(nullptr) : spread_json(st.node_count)},
                     {"triangle_count", meshes.empty() ? nlohmann::json(nullptr) : spread_json(st.triangle_count)},
                     {"burr_draws", {{"count", st.drawn}, {"ks_statistic", st.ks_drawn}, {"ks_p_value", st.ks_drawn_p}}},
                     {"placed_pores",
                      {{"count", st.placed}, {"ks_statistic", st.ks_placed}, {"ks_p_value", st.ks_placed_p}}}});
    for (const HistogramBin& b : st.histogram)
      csv += fmt::format("{},{},{},{},{},{},{},{}\n", st.side_m, b.lo_m, b.hi_m, b.drawn, b.placed, b.drawn_density_1_m,
                         b.placed_density_1_m, b.burr_density_1_m);
    std::printf("%8.2f %6zu %8.1f [%3.0f,%3.0f] %9.1f %9.1f/%9.1f %9.5f [%.5f,%.5f] %8.0f [%5.0f,%5.0f]\n",
                st.side_m * 1e3, st.cells, st.pore_count.mean, st.pore_count.min, st.pore_count.max,
                st.expected_pore_count, st.largest_pore_m.mean * 1e6, st.largest_pore_m.max * 1e6, st.porosity.mean,
                st.porosity.min, st.porosity.max, st.node_count.mean, st.node_count.min, st.node_count.max);
  }
  progress.finish();
  const CellSettings& s0 = per_size.front();
  const Provenance provenance = Provenance::make("uhpc-micro generate-ensemble",
                                                 fnv1a64_hex(cfg.hash() + s0.config_hash), e.base_seed);
  const nlohmann::json statistics = {{"format", "uhpc-micro-generate-ensemble/1"},
                                     {"base_seed", e.base_seed},
                                     {"realizations", e.realizations},
                                     {"seed_rule", "derive_cell_seed(base_seed, size_index, realization): SplitMix64 chain, 53 bits"},
                                     {"truncation_m", s0.cell.truncation_m},
                                     {"porosity_target", s0.cell.porosity.target},
                                     {"porosity_tolerance", s0.cell.porosity.tolerance},
                                     {"nominal_spacing_m", s0.mesh.nominal_spacing_m},
                                     {"sizes", sizes},
                                     {"histogram_file", "pore_histogram.csv"},
                                     {"provenance", provenance.to_json()}};
  write_text_atomic(out / "statistics.json", statistics.dump(2) + "\n");
  write_text_atomic(out / "pore_histogram.csv", csv);
  const double elapsed = seconds_since(t0);
  std::printf("generated %zu cells in %.1f s\n", e.sizes_m.size() * static_cast<std::size_t>(e.realizations), elapsed);
  spdlog::info("wrote {} and {}", (out / "statistics.json").string(), (out / "pore_histogram.csv").string());
  return kExitOk;
}

}  // namespace uhpc::micro

namespace uhpc::micro {

namespace {

nlohmann::json elastic_json(const ElasticSettings& s, const GeneratedCell& cell, const UniaxialResult& r,
                            double mesh_s, const Provenance& provenance) {
  const CellGeometry& g = cell.geometry;
  const UniaxialOptions& o = s.options;
  return {{"format", "uhpc-micro-elastic/1"},
          {"cell",
           {{"cell_size_m", g.side_m},
            {"seed", s.cell.seed},
            {"pore_count", g.pores.size()},
            {"porosity", g.porosity()},
            {"loading_direction", g.load == LoadAxis::X ? "x" : "y"},
            {"nominal_spacing_m", s.cell.mesh.nominal_spacing_m}}},
          {"matrix",
           {{"youngs_modulus_Pa", s.material.youngs_modulus_Pa},
            {"poissons_ratio", s.material.poissons_ratio},
            {"plane_strain_modulus_Pa", s.material.plane_modulus_Pa()}}},
          {"loading",
           {{"strain", r.strain},
            {"imposed_displacement_m", r.strain * g.side_m},
            {"far_face_mean_displacement_m", r.far_face_mean_displacement_m}}},
          {"E0_bar_Pa", r.E0_bar_Pa},
          {"E0_bar_over_plane_strain_modulus", r.E0_bar_Pa / s.material.plane_modulus_Pa()},
          {"sigma_bar_Pa", r.sigma_bar_Pa},
          {"reactions_N_per_m",
           {{"far_face", r.far_face_force_N_m},
            {"near_face", r.near_face_force_N_m},
            {"imbalance_relative", (r.far_face_force_N_m + r.near_face_force_N_m) / r.far_face_force_N_m},
            {"transverse_point", r.point_force_N_m},
            {"transverse_point_relative", r.point_force_N_m / r.far_face_force_N_m}}},
          {"energy",
           {{"strain_energy_density_J_m3", r.energy_density_J_m3},
            {"half_sigma_bar_e_bar_J_m3", r.half_sigma_e_J_m3},
            {"hill_mandel_relative_difference", r.hill_mandel_relative}}},
          {"discretization",
           {{"nodes", r.nodes},
            {"dofs", r.dofs},
            {"domain_points", r.domain_points},
            {"boundary_points", r.boundary_points},
            {"quasi_linear_points", r.quasi_linear_points},
            {"vci_max_correction", r.vci_max_correction}}},
          {"options",
           {{"rk_support_factor", o.rk.support_factor},
            {"rk_kernel", kernel_name(o.rk.kernel)},
            {"rk_basis", "linear"},
            {"gradients", rk::derivatives_name(o.rk.derivatives)},
            {"triangle_points", o.rk.triangle_points},
            {"segment_points", o.rk.segment_points},
            {"integration_correction", o.rk.correction == IntegrationCorrection::Vci ? "vci" : "none"},
            {"essential_bc", "nitsche"},
            {"nitsche_factor", o.nitsche_factor},
            {"transverse_fix", "point penalty at the midpoint of the near face"}}},
          {"solver", {{"name", r.solver}, {"relative_residual", r.solver_relative_residual}}},
          {"timing_s",
           {{"generate_and_mesh", mesh_s},
            {"shape_functions", r.model_s},
            {"assembly", r.assembly_s},
            {"solve", r.solve_s}}},
          {"provenance", provenance.to_json()}};
}

}  // namespace

int run_elastic(const std::string& config_path, const std::vector<std::string>& overrides, const fs::path& out) {
  const auto t0 = std::chrono::steady_clock::now();
  const ElasticSettings s = load_elastic_settings(config_path, overrides);
  const OutputLock lock = lock_output_directory(out, "uhpc-micro elastic");
  const GeneratedCell cell = generate_or_explain(s.cell, s.cell_config);
  const CellDiscretization mesh = mesh_cell(cell.geometry, s.cell.mesh);
  const double mesh_s = seconds_since(t0);
  const CellGeometry& g = cell.geometry;
  const UniaxialResult r = uniaxial_elastic_response(mesh, g.side_m, g.load, s.material, s.options);
  const Provenance provenance = Provenance::make("uhpc-micro elastic", s.config_hash, s.cell.seed);
  write_text_atomic(out / "elastic.json", elastic_json(s, cell, r, mesh_s, provenance).dump(2) + "\n");
  std::printf("cell %.2f mm, seed %llu: %zu pores, porosity %.5f; %zu nodes, %zu DOFs\n", g.side_m * 1e3,
              static_cast<unsigned long long>(s.cell.seed), g.pores.size(), g.porosity(), r.nodes, r.dofs);
  std::printf("E0_bar = %.1f MPa (%.4f x E/(1-nu^2)), sigma_bar = %.4f MPa at e_bar = %g; "
              "energy check (Psi - sigma e/2)/(sigma e/2) = %.2e\n",
              r.E0_bar_Pa * 1e-6, r.E0_bar_Pa / s.material.plane_modulus_Pa(), r.sigma_bar_Pa * 1e-6, r.strain,
              r.hill_mandel_relative);
  spdlog::info("wrote {} in {:.2f} s (mesh {:.2f}, shape functions {:.2f}, assembly {:.2f}, solve {:.2f})",
               (out / "elastic.json").string(), seconds_since(t0), mesh_s, r.model_s, r.assembly_s, r.solve_s);
  return kExitOk;
}

}  // namespace uhpc::micro
