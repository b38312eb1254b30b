// uhpc-calibrate: fits the SDEL constants {a, A, nu, chi} to the per-size mean damage curves of a
// microcell ensemble (all sizes at once, Ceres, docs/physics.md section 3) and the size effect law to the
// nominal strengths; writes the micro-to-macro handoff sdel.json, a fit report and figure data.
//
//   uhpc-calibrate --ensemble ENSEMBLE.h5 --out sdel.json [--config data/calibrate.json] [--report DIR]
//                  [--set key=value]
//   uhpc-calibrate synthesize --sdel data/sdel_paper.json --out ensemble.h5
//                  [--config data/synthetic_ensemble.json] [--noise 0.01] [--seed N] [--set key=value]
//
// The second form writes an ensemble file in the format uhpc-micro ensemble writes (uhpc/ensemble_file.hpp)
// from a known SDEL, so the chain can be exercised and tested without microcell runs.
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glog/logging.h>
#include <nlohmann/json.hpp>

#include "calibrate_config.hpp"
#include "calibrate_report.hpp"
#include "uhpc/ensemble_file.hpp"
#include "ensemble_fit_data.hpp"
#include "sdel_fit.hpp"
#include "size_effect_fit.hpp"
#include "synthetic_ensemble.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/config.hpp"
#include "uhpc/data_dir.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/logging.hpp"
#include "uhpc/output_lock.hpp"
#include "uhpc/provenance.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace fs = std::filesystem;

namespace {

// The shipped defaults (uhpc/data_dir.hpp), so every command runs without a hand-written input.
std::string shipped_or(const std::string& given, const char* name) {
  return given.empty() ? (uhpc::shipped_data_dir() / name).string() : given;
}

void print_fit(const uhpc::SdelFitResult& fit, const uhpc::SizeEffectFit& se, const uhpc::Ensemble& e) {
  const double v[4] = {fit.constants.a, fit.constants.A, fit.constants.nu, fit.constants.chi};
  std::printf("%-4s %14s %14s %10s %13s\n", "", "value", "std_error", "rel_se", "identifiable");
  for (std::size_t i = 0; i < 4; ++i) {
    std::printf("%-4s %14.6g %14.4g %10.3g %13s\n", uhpc::kSdelConstantNames[i], v[i], fit.standard_error[i],
                fit.relative_standard_error[i], fit.identifiable[i] ? "yes" : "NO");
  }
  std::printf("\n%9s %8s %12s %12s %10s\n", "size_mm", "samples", "rms", "max_abs", "R^2");
  for (std::size_t k = 0; k < fit.sizes.size(); ++k) {
    const auto& q = fit.sizes[k];
    std::printf("%9.3f %8d %12.4e %12.4e %10.6f\n", e.sizes_m[k] * 1e3, q.samples, q.rms, q.max_abs, q.r_squared);
  }
  for (const auto& note : fit.notes) std::printf("note: %s\n", note.c_str());
  if (se.size_effect) {
    std::printf("\nsize effect law: B = %.5g (se %.3g), D0 = %.5g mm (se %.3g mm), f_t = %.4g MPa, rms %.4g MPa, "
                "R^2 %.5f\n",
                se.B, se.standard_error[0], se.D0_m * 1e3, se.standard_error[1] * 1e3, se.f_t_Pa * 1e-6,
                se.rms_Pa * 1e-6, se.r_squared);
  } else {
    std::printf("\nsize effect law: %s\n", se.note.c_str());
  }
}

// A fit no start could finish writes REPORT_DIR/fit_diagnostic.json (the inputs and every start: where
// it began, where it ended, the solver's message) and returns the one-line message naming the input.
std::string write_fit_diagnostic(const uhpc::SdelFitFailure& failure, const std::string& ensemble_path,
                                 const std::string& config_path, const uhpc::CalibrateSettings& settings,
                                 const fs::path& report_dir, const uhpc::Config& cfg) {
  const fs::path path = report_dir / "fit_diagnostic.json";
  const nlohmann::json diagnostic = {{"failure", failure.what()},
                                     {"ensemble", ensemble_path},
                                     {"config", config_path},
                                     {"settings", uhpc::fit_settings_json(settings)},
                                     {"starts", uhpc::sdel_starts_json(failure.starts)},
                                     {"provenance", uhpc::Provenance::make("uhpc-calibrate", cfg.hash()).to_json()}};
  fs::create_directories(report_dir);
  uhpc::write_text_atomic(path, diagnostic.dump(2) + "\n");
  return fmt::format("{}: {} ({} starts; each start's end and the solver's message in {})", ensemble_path,
                     failure.what(), failure.starts.size(), path.string());
}

int calibrate(const std::string& ensemble_path, const std::string& config_path,
              const std::vector<std::string>& overrides, const fs::path& out, fs::path report_dir) {
  const uhpc::Config cfg = uhpc::Config::load(config_path, overrides);
  const uhpc::CalibrateSettings settings = uhpc::read_calibrate_settings(cfg);
  const uhpc::Ensemble ensemble = uhpc::read_ensemble(ensemble_path);
  if (ensemble.size_count() < 2) {
    throw uhpc::InputError(fmt::format(
        "{}: dataset '/sizes': only one size ({} m), but a and A cannot both be fitted from one size, where e_i = "
        "A / sqrt(1 + a lambda) is a single number: the fit needs at least 2 sizes",
        ensemble_path, ensemble.sizes_m.front()));
  }
  // The outputs are checked and taken before the fit (minutes on a large ensemble), not found unusable after
  // it: --out and the report directory are this run's alone until it ends.
  const uhpc::OutputLock out_lock = uhpc::lock_output_file(out, "uhpc-calibrate");
  if (report_dir.empty()) report_dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  const uhpc::OutputLock report_lock = uhpc::lock_output_directory(report_dir, "uhpc-calibrate");
  for (const char* name : {"fit_report.json", "calibration_figures.h5", "fit_diagnostic.json"})
    uhpc::require_file_path(report_dir / name);
  fs::remove(report_dir / "fit_diagnostic.json");  // an earlier failure's, which this run replaces or clears
  uhpc::SdelFitResult fit;
  try {
    fit = uhpc::fit_sdel(uhpc::fit_data_from_ensemble(ensemble, settings.l_mac_m), settings.fit);
  } catch (const std::invalid_argument& e) {
    throw uhpc::InputError(ensemble_path + ": dataset '/damage/mean': " + e.what());
  } catch (const uhpc::SdelFitFailure& failure) {
    throw uhpc::NumericalError(write_fit_diagnostic(failure, ensemble_path, config_path, settings, report_dir, cfg));
  }
  const uhpc::SizeEffectFit size_effect =
      uhpc::fit_size_effect(ensemble.sizes_m, ensemble.nominal_strength_Pa, settings.f_t_Pa);
  spdlog::info("fitted {} samples of {} sizes from {} ({} starts, best: {})", fit.samples, ensemble.size_count(),
               ensemble_path, fit.starts.size(), fit.starts[static_cast<std::size_t>(fit.best_start)].origin);

  const uhpc::Provenance provenance = uhpc::Provenance::make("uhpc-calibrate", cfg.hash());
  nlohmann::json source_provenance = ensemble.provenance ? ensemble.provenance->to_json() : nlohmann::json();
  uhpc::SdelHandoff handoff;
  handoff.constants = fit.constants;
  handoff.l_mac_m = settings.l_mac_m;
  handoff.strain_measure = settings.strain_measure;
  handoff.cell_sizes_m = ensemble.sizes_m;
  handoff.source = "uhpc-calibrate: least-squares fit (paper eq. 27) of the SDEL to the mean damage curves of " +
                   ensemble_path + " (made by " + (ensemble.provenance ? ensemble.provenance->program : "?") + ")";
  handoff.fit = {{"settings", uhpc::fit_settings_json(settings)},
                 {"sdel", uhpc::sdel_fit_json(fit, ensemble, false)},
                 {"size_effect", uhpc::size_effect_json(size_effect, ensemble)},
                 {"ensemble", {{"file", ensemble_path}, {"provenance", source_provenance}}}};
  handoff.provenance = provenance;
  uhpc::write_sdel_handoff(out.string(), handoff);

  nlohmann::json report = {{"ensemble", {{"file", ensemble_path}, {"provenance", source_provenance}}},
                           {"handoff", out.string()},
                           {"settings", uhpc::fit_settings_json(settings)},
                           {"sdel", uhpc::sdel_fit_json(fit, ensemble, true)},
                           {"size_effect", uhpc::size_effect_json(size_effect, ensemble)},
                           {"provenance", provenance.to_json()}};
  uhpc::write_text_atomic(report_dir / "fit_report.json", report.dump(2) + "\n");
  uhpc::write_figure_data(report_dir / "calibration_figures.h5", ensemble, settings, fit, size_effect, provenance);
  print_fit(fit, size_effect, ensemble);
  spdlog::info("wrote {}, {} and {}", out.string(), (report_dir / "fit_report.json").string(),
               (report_dir / "calibration_figures.h5").string());
  return uhpc::kExitOk;
}

int synthesize(const std::string& sdel_path, const std::string& config_path, const std::vector<std::string>& overrides,
               const fs::path& out) {
  const uhpc::SdelHandoff handoff = uhpc::read_sdel_handoff(sdel_path);
  const uhpc::Config cfg = uhpc::Config::load(config_path, overrides);
  const uhpc::SyntheticEnsembleSettings s = uhpc::read_synthetic_settings(cfg, handoff.l_mac_m);
  const uhpc::OutputLock lock = uhpc::lock_output_file(out, "uhpc-calibrate synthesize");
  const uhpc::Ensemble e = uhpc::synthesize_ensemble(handoff.constants, s);
  uhpc::write_ensemble(out, e, uhpc::Provenance::make("uhpc-calibrate synthesize", cfg.hash(), s.seed));
  spdlog::info("wrote {}: {} sizes x {} strains from {} (noise {}, seed {})", out.string(), e.size_count(),
               e.strain_count(), sdel_path, s.noise_std, s.seed);
  return uhpc::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Fits the SDEL constants {a, A, nu, chi} to a microcell ensemble (all sizes at once) and the size "
               "effect law to its nominal strengths; writes the handoff sdel.json, fit_report.json and "
               "calibration_figures.h5.",
               "uhpc-calibrate"};
  app.require_subcommand(0, 1);
  std::string ensemble, out, report, config;
  std::vector<std::string> overrides;
  app.add_option("--ensemble", ensemble, "ensemble file (HDF5) written by uhpc-micro ensemble or synthesize");
  app.add_option("--out", out, "the handoff file to write (sdel.json)");
  app.add_option("--config", config, "settings (JSON); default: calibrate.json of the shipped data");
  app.add_option("--report", report, "directory for fit_report.json and calibration_figures.h5 "
                                     "(default: the directory of --out)");
  uhpc::add_set_option(app, overrides);

  CLI::App* synth = app.add_subcommand("synthesize", "Writes an ensemble file from an SDEL handoff (optionally "
                                                     "with seeded Gaussian noise), in the format uhpc-micro writes");
  std::string syn_sdel, syn_out, syn_config;
  std::vector<std::string> syn_overrides;
  double noise = 0;
  long long seed = 0;
  synth->add_option("--sdel", syn_sdel, "SDEL handoff to generate the curves from")->required();
  synth->add_option("--out", syn_out, "ensemble file to write (HDF5)")->required();
  synth->add_option("--config", syn_config, "settings (JSON); default: synthetic_ensemble.json of the shipped data");
  auto* noise_opt = synth->add_option("--noise", noise, "shortcut for --set noise_std=VALUE");
  auto* seed_opt = synth->add_option("--seed", seed, "shortcut for --set seed=VALUE");
  uhpc::add_set_option(*synth, syn_overrides);

  return uhpc::run_main(app, [&] {
    app.parse(argc, argv);
    uhpc::init_logging("uhpc-calibrate");
    // Ceres logs through glog to stderr (e.g. a rank-deficient covariance); the program reports such
    // findings itself, in its notes, so stderr keeps the one-line error contract.
    FLAGS_minloglevel = google::GLOG_FATAL;
    if (synth->parsed()) {
      syn_config = shipped_or(syn_config, "synthetic_ensemble.json");
      // The shortcuts are overrides like any --set, so the config hash (provenance) includes them.
      if (noise_opt->count() > 0) syn_overrides.push_back(fmt::format("noise_std={}", noise));
      if (seed_opt->count() > 0) syn_overrides.push_back(fmt::format("seed={}", seed));
      return synthesize(syn_sdel, syn_config, syn_overrides, syn_out);
    }
    if (ensemble.empty()) throw uhpc::InputError("--ensemble is required");
    if (out.empty()) throw uhpc::InputError("--out is required");
    return calibrate(ensemble, shipped_or(config, "calibrate.json"), overrides, out, report);
  });
}
