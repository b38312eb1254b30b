#pragma once
// Reading CellAnalysisOptions from a configuration section (e.g. "analysis" of the run config) and
// the cohesive matrix of Table 2 from the microstructure file's "matrix" section. Every key is
// optional (the defaults of cell_analysis.hpp apply) but validated when present; an unknown key is an
// error at the caller's finish(). Errors are uhpc::InputError "<file>: key 'k': reason".
//
// Keys (section-relative; defaults in cell_analysis.hpp):
//   rk.support_factor, rk.kernel ("cubic_bspline" | "quartic_spline"), rk.derivatives ("direct" | "implicit"),
//   quadrature.triangle_points (1, 3, 6, 7, 12), quadrature.segment_points (1..5),
//   quadrature.correction ("vci" | "none"), quadrature.crack_points (1..5),
//   quadrature.cracked_correction ("none" | "vci"),
//   essential_bc.nitsche_factor,
//   enrichment.tip ("ramped"), enrichment.min_ratio,
//   cohesive.activation_ratio (0, 0.1], cohesive.contact_penalty_ratio, cohesive.residual_stiffness_ratio
//   (0, 1e-3], cohesive.mode ("mode_i" | "mixed"),
//   growth.increment_spacings, growth.average_radius_spacings, growth.coalescence_spacings, growth.tolerance, growth.max_per_step,
//   path.control ("crack_opening" | "displacement"), path.elastic_states, path.opening_increment,
//   path.min_opening_increment, path.max_opening_increment, path.strain_increment,
//   path.min_strain_increment, path.max_strain_increment, path.step_growth, path.easy_iterations,
//   path.max_steps, path.max_strain (default: curve_end_strain when given, else the solver's own; never
//   below curve_end_strain), path.separation_fraction,  growth.fallback ("unload_and_regrow" | "fail" |
//   "relax"), growth.field_transfer, growth.hold, path.zone_control ("fallback" | "off"),
//   newton.max_iterations, newton.line_search_halvings, newton.tolerance.
#include <optional>

#include "cell_analysis.hpp"
#include "uhpc/config.hpp"

namespace uhpc::micro {

// `curve_end_strain`: the strain the path must reach (the drivers' strain-grid end), if any.
CellAnalysisOptions read_cell_analysis_options(const Config& section, std::optional<double> curve_end_strain = {});

// youngs_modulus_Pa, poissons_ratio, tensile_strength_Pa, fracture_energy_J_m2 (all required).
CellMaterial read_cell_material(const Config& matrix);

}  // namespace uhpc::micro
