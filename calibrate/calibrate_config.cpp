#include "calibrate_config.hpp"

#include "uhpc/sdel_handoff.hpp"

namespace uhpc {

CalibrateSettings read_calibrate_settings(const Config& cfg) {
  CalibrateSettings s;
  s.l_mac_m = cfg.number("l_mac_m", Range::positive());
  s.f_t_Pa = cfg.number("f_t_Pa", Range::positive());
  s.strain_measure =
      cfg.choice("strain_measure", {kSdelStrainEffectiveTensile, kSdelStrainMazars, kSdelStrainMaxPrincipal});
  s.figure_points = static_cast<int>(cfg.integer("figure_points", Range::closed(2, 1e6)));

  SdelFitOptions& f = s.fit;
  f.weighting = cfg.choice("weighting", {"none", "spread"}) == "spread" ? SdelWeighting::Spread : SdelWeighting::None;
  f.starts = static_cast<int>(cfg.integer("starts", Range::closed(1, 100)));
  f.damage_resolution = cfg.number("damage_resolution", Range::open(0.0, 1.0));
  f.a_lower_bound = cfg.number("a_lower_bound", Range::positive());

  const Config samples = cfg.section("samples");
  f.strain_min = samples.number("strain_min", Range::at_least(0.0));
  f.strain_max = samples.number("strain_max", Range::positive());
  if (!(f.strain_max > f.strain_min)) samples.fail("strain_max", "must be > samples.strain_min");
  f.damage_window = samples.flag("damage_window");
  f.damage_min = samples.number("damage_min", Range::closed(0.0, 1.0));
  f.damage_max = samples.number("damage_max", Range::closed(0.0, 1.0));
  if (!(f.damage_max > f.damage_min)) samples.fail("damage_max", "must be > samples.damage_min");

  const Config solver = cfg.section("solver");
  f.max_iterations = static_cast<int>(solver.integer("max_iterations", Range::closed(1, 1e6)));
  f.function_tolerance = solver.number("function_tolerance", Range::positive());
  f.gradient_tolerance = solver.number("gradient_tolerance", Range::positive());
  f.parameter_tolerance = solver.number("parameter_tolerance", Range::positive());

  const Config ident = cfg.section("identifiability");
  f.max_relative_standard_error = ident.number("max_relative_standard_error", Range::positive());
  f.max_abs_correlation = ident.number("max_abs_correlation", Range::open(0.0, 1.0));
  f.min_a_lambda = ident.number("min_a_lambda", Range::positive());
  cfg.finish();
  return s;
}

SyntheticEnsembleSettings read_synthetic_settings(const Config& cfg, double l_mac_m) {
  SyntheticEnsembleSettings s;
  s.l_mac_m = l_mac_m;
  s.sizes_m = cfg.numbers("sizes_m", Range::positive());
  for (std::size_t k = 1; k < s.sizes_m.size(); ++k) {
    if (!(s.sizes_m[k] > s.sizes_m[k - 1])) cfg.fail("sizes_m", "must be strictly ascending");
  }
  s.strain_max = cfg.number("strain_max", Range::open(0.0, 1.0));
  s.points = static_cast<int>(cfg.integer("points", Range::closed(2, 1e6)));
  s.youngs_modulus_Pa = cfg.number("youngs_modulus_Pa", Range::positive());
  s.cells = cfg.integer("cells", Range::closed(1, 1e9));
  s.noise_std = cfg.number("noise_std", Range::closed(0.0, 1.0));
  s.seed = static_cast<std::uint64_t>(cfg.integer("seed", Range::closed(0, 9.0e18)));
  cfg.finish();
  return s;
}

}  // namespace uhpc
