#include "calibrate_report.hpp"

#include <cmath>
#include <cstdint>

#include "ensemble_fit_data.hpp"
#include "uhpc/hdf5_io.hpp"

namespace uhpc {
namespace {

nlohmann::json named(const std::array<double, 4>& v) {
  nlohmann::json j;
  for (std::size_t i = 0; i < 4; ++i) j[kSdelConstantNames[i]] = v[i];
  return j;
}
nlohmann::json matrix(const std::array<std::array<double, 4>, 4>& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : m) rows.push_back(r);
  return rows;
}
nlohmann::json constants_json(const SdelConstants<double>& c) {
  return {{"a", c.a}, {"A", c.A}, {"nu", c.nu}, {"chi", c.chi}};
}

}  // namespace

nlohmann::json sdel_starts_json(const std::vector<SdelStart>& starts) {
  nlohmann::json out = nlohmann::json::array();
  for (const SdelStart& s : starts) {
    out.push_back({{"origin", s.origin},
                   {"initial", constants_json(s.initial)},
                   {"final", constants_json(s.final)},
                   {"cost", s.cost},
                   {"converged", s.converged},
                   {"iterations", s.iterations},
                   {"message", s.message}});
  }
  return out;
}

nlohmann::json sdel_fit_json(const SdelFitResult& fit, const Ensemble& ensemble, bool with_starts) {
  nlohmann::json identifiable;
  for (std::size_t i = 0; i < 4; ++i) identifiable[kSdelConstantNames[i]] = fit.identifiable[i];
  nlohmann::json per_size = nlohmann::json::array();
  for (std::size_t k = 0; k < fit.sizes.size(); ++k) {
    const SdelSizeQuality& q = fit.sizes[k];
    per_size.push_back({{"size_m", ensemble.sizes_m[k]},
                        {"lambda", q.lambda},
                        {"samples", q.samples},
                        {"rms", q.rms},
                        {"max_abs_residual", q.max_abs},
                        {"r_squared", q.r_squared}});
  }
  nlohmann::json j = {
      {"constants", constants_json(fit.constants)},
      {"standard_errors", named(fit.standard_error)},
      {"relative_standard_errors", named(fit.relative_standard_error)},
      {"identifiable", identifiable},
      {"a_lambda_max", fit.a_lambda_max},
      {"a_weakly_identifiable", fit.a_weak},
      {"a_at_lower_bound", fit.a_at_lower_bound},
      {"covariance_available", fit.covariance_ok},
      {"covariance", {{"order", {"a", "A", "nu", "chi"}}, {"matrix", matrix(fit.covariance)}}},
      {"correlation", {{"order", {"a", "A", "nu", "chi"}}, {"matrix", matrix(fit.correlation)}}},
      {"residual_scale", fit.residual_scale},
      {"residual_scale_raw", fit.residual_scale_raw},
      {"samples", fit.samples},
      {"cost", fit.cost},
      {"notes", fit.notes},
      {"per_size", per_size},
      {"best_start", fit.best_start},
      {"starts_run", fit.starts.size()},
      {"starts_agreeing", fit.starts_agreeing}};
  if (with_starts) j["starts"] = sdel_starts_json(fit.starts);
  return j;
}

nlohmann::json size_effect_json(const SizeEffectFit& fit, const Ensemble& ensemble) {
  return {{"law", "sigma_N = B f_t / sqrt(1 + D / D0), D = cell size"},
          {"size_effect", fit.size_effect},
          {"note", fit.note},
          {"B", fit.B},
          {"D0_m", fit.D0_m},
          {"f_t_Pa", fit.f_t_Pa},
          {"standard_errors", {{"B", fit.standard_error[0]}, {"D0_m", fit.standard_error[1]}}},
          {"correlation_B_D0", fit.correlation},
          {"rms_Pa", fit.rms_Pa},
          {"r_squared", fit.r_squared},
          {"sizes_m", ensemble.sizes_m},
          {"nominal_strength_Pa", ensemble.nominal_strength_Pa},
          {"fitted_Pa", fit.fitted_Pa}};
}

nlohmann::json fit_settings_json(const CalibrateSettings& s) {
  const SdelFitOptions& f = s.fit;
  return {{"weighting", f.weighting == SdelWeighting::Spread ? "spread" : "none"},
          {"starts", f.starts},
          {"samples",
           {{"strain_min", f.strain_min},
            {"strain_max", f.strain_max},
            {"damage_window", f.damage_window},
            {"damage_min", f.damage_min},
            {"damage_max", f.damage_max}}},
          {"damage_resolution", f.damage_resolution},
          {"a_lower_bound", f.a_lower_bound},
          {"l_mac_m", s.l_mac_m},
          {"f_t_Pa", s.f_t_Pa}};
}

void write_figure_data(const std::filesystem::path& path, const Ensemble& e, const CalibrateSettings& settings,
                       const SdelFitResult& fit, const SizeEffectFit& size_effect, const Provenance& provenance) {
  const std::size_t n = e.size_count(), m = e.strain_count();
  const auto mask = sdel_fit_mask(fit_data_from_ensemble(e, settings.l_mac_m), settings.fit);
  std::vector<double> mean, stdev, law;
  std::vector<std::uint8_t> fitted;
  for (std::size_t k = 0; k < n; ++k) {
    const double lambda = e.sizes_m[k] / settings.l_mac_m;
    for (std::size_t j = 0; j < m; ++j) {
      mean.push_back(e.damage_mean[k][j]);
      stdev.push_back(e.damage_std[k][j]);
      law.push_back(sdel_damage(lambda, e.strain[j], fit.constants));
      fitted.push_back(mask[k][j] ? 1 : 0);
    }
  }
  // Fig. 10: the law on a geometric size grid from half the smallest to twice the largest cell.
  const auto points = static_cast<std::size_t>(settings.figure_points);
  const double lo = 0.5 * e.sizes_m.front(), hi = 2.0 * e.sizes_m.back();
  std::vector<double> grid, strength;
  for (std::size_t i = 0; i < points; ++i) {
    const double D = lo * std::pow(hi / lo, static_cast<double>(i) / static_cast<double>(points - 1));
    grid.push_back(D);
    strength.push_back(size_effect.size_effect ? size_effect_strength(size_effect.B, size_effect.f_t_Pa,
                                                                      size_effect.D0_m, D)
                                               : size_effect.B * size_effect.f_t_Pa);
  }

  H5Writer w(path);
  w.write("fig11/sizes", e.sizes_m, "m");
  w.write("fig11/strain", e.strain, "1");
  w.write("fig11/damage_mean", mean, {n, m}, "1");
  w.write("fig11/damage_std", stdev, {n, m}, "1");
  w.write("fig11/damage_fit", law, {n, m}, "1");
  w.write("fig11/fitted", fitted.data(), {n, m}, "1");
  w.write("fig10/sizes", e.sizes_m, "m");
  w.write("fig10/nominal_strength", e.nominal_strength_Pa, "Pa");
  w.write("fig10/size_grid", grid, "m");
  w.write("fig10/law", strength, "Pa");
  w.set_attribute("fig10", "B", size_effect.B);
  w.set_attribute("fig10", "D0_m", size_effect.D0_m);
  w.set_attribute("fig10", "f_t_Pa", size_effect.f_t_Pa);
  w.set_attribute("fig10", "size_effect", static_cast<std::int64_t>(size_effect.size_effect ? 1 : 0));
  for (std::size_t i = 0; i < 4; ++i) {
    const double v[4] = {fit.constants.a, fit.constants.A, fit.constants.nu, fit.constants.chi};
    w.set_attribute("fig11", kSdelConstantNames[i], v[i]);
  }
  w.write_provenance(provenance);
  w.close();
}

}  // namespace uhpc
