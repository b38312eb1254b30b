#pragma once
// What uhpc-calibrate reports: the fit as JSON (the handoff's "fit" block and fit_report.json) and the
// data of the two figures (calibration_figures.h5: the paper's Fig. 11, damage curves with the fitted
// law per size, and Fig. 10, nominal strength against size with the fitted size effect law).
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "calibrate_config.hpp"
#include "uhpc/ensemble_file.hpp"
#include "sdel_fit.hpp"
#include "size_effect_fit.hpp"
#include "uhpc/provenance.hpp"

namespace uhpc {

// The SDEL fit: constants, standard errors, covariance, identifiability, per-size quality; with
// `with_starts` also every start (the report has them, the handoff does not need them).
// Every start of a fit: origin, initial and final constants, cost, convergence, the solver's message.
nlohmann::json sdel_starts_json(const std::vector<SdelStart>& starts);
nlohmann::json sdel_fit_json(const SdelFitResult& fit, const Ensemble& ensemble, bool with_starts);
nlohmann::json size_effect_json(const SizeEffectFit& fit, const Ensemble& ensemble);
// The fit options as they were applied (echoed into the report and the handoff).
nlohmann::json fit_settings_json(const CalibrateSettings& settings);

// Writes `path` (HDF5) with /fig11/... and /fig10/...; see calibrate/README.md for the layout.
void write_figure_data(const std::filesystem::path& path, const Ensemble& ensemble, const CalibrateSettings& settings,
                       const SdelFitResult& fit, const SizeEffectFit& size_effect, const Provenance& provenance);

}  // namespace uhpc
