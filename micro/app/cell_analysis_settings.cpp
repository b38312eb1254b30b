#include "cell_analysis_settings.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "quadrature.hpp"

namespace uhpc::micro {

namespace {

// Optional getters: the default stays when the key is absent.
void opt(const Config& c, const std::string& key, double& v, const Range& r) {
  if (c.has(key)) v = c.number(key, r);
}
void opt(const Config& c, const std::string& key, int& v, Range r) {
  // The range clipped to int's, so that 4294967296 steps is refused rather than wrapped to 0.
  r.lo = std::max(r.lo, static_cast<double>(std::numeric_limits<int>::min()));
  r.hi = std::min(r.hi, static_cast<double>(std::numeric_limits<int>::max()));
  if (c.has(key)) v = static_cast<int>(c.integer(key, r));
}

}  // namespace

CellAnalysisOptions read_cell_analysis_options(const Config& c, std::optional<double> curve_end_strain) {
  CellAnalysisOptions o;
  if (curve_end_strain) o.max_strain = *curve_end_strain;
  opt(c, "rk.support_factor", o.rk.support_factor, Range::closed(1.0, 4.0));
  if (c.has("rk.kernel")) o.rk.kernel = kernel_from_name(c.choice("rk.kernel", {"cubic_bspline", "quartic_spline"}));
  if (c.has("rk.derivatives")) o.rk.derivatives = rk::derivatives_from_name(c.choice("rk.derivatives", {"implicit", "direct"}));
  opt(c, "quadrature.triangle_points", o.rk.triangle_points, Range::closed(1, 12));
  if (!is_triangle_rule(o.rk.triangle_points))
    c.fail("quadrature.triangle_points",
           "value " + std::to_string(o.rk.triangle_points) + " is not one of: 1, 3, 6, 7, 12");
  opt(c, "quadrature.segment_points", o.rk.segment_points, Range::closed(1, 5));
  if (c.has("quadrature.correction"))
    o.rk.correction = c.choice("quadrature.correction", {"vci", "none"}) == "vci" ? IntegrationCorrection::Vci
                                                                                 : IntegrationCorrection::None;
  opt(c, "quadrature.crack_points", o.enrichment.crack_points, Range::closed(1, 5));
  if (c.has("quadrature.cracked_correction"))
    o.enrichment.cracked_correction = c.choice("quadrature.cracked_correction", {"none", "vci"}) == "none"
                                          ? IntegrationCorrection::None
                                          : IntegrationCorrection::Vci;
  opt(c, "essential_bc.nitsche_factor", o.nitsche_factor, Range::positive());
  if (c.has("enrichment.tip")) c.choice("enrichment.tip", {"ramped"});
  opt(c, "enrichment.min_ratio", o.enrichment.min_enrichment_ratio, Range{0.0, 0.1, false, true});
  opt(c, "cohesive.activation_ratio", o.activation_ratio, Range{0.0, 0.1, true, false});
  opt(c, "cohesive.contact_penalty_ratio", o.contact_penalty_ratio, Range::positive());
  opt(c, "cohesive.residual_stiffness_ratio", o.residual_stiffness_ratio, Range{0.0, 1e-3, true, false});
  if (c.has("cohesive.mode"))
    o.mode = c.choice("cohesive.mode", {"mode_i", "mixed"}) == "mixed" ? CohesiveMode::MixedMode : CohesiveMode::ModeI;
  opt(c, "growth.increment_spacings", o.growth.increment_spacings, Range::closed(0.25, 4.0));
  opt(c, "growth.average_radius_spacings", o.growth.average_radius_spacings, Range::closed(0.5, 8.0));
  opt(c, "growth.coalescence_spacings", o.growth.coalescence_spacings, Range::closed(0.0, 4.0));
  opt(c, "growth.tolerance", o.growth_tolerance, Range::positive());
  opt(c, "growth.max_per_step", o.max_growth_per_step, Range::at_least(1));
  if (c.has("growth.fallback")) {
    const std::string f = c.choice("growth.fallback", {"unload_and_regrow", "fail", "relax"});
    o.growth_fallback = f == "fail"    ? GrowthFallback::Fail
                        : f == "relax" ? GrowthFallback::Relax
                                       : GrowthFallback::UnloadAndRegrow;
  }
  if (c.has("growth.field_transfer"))
    o.field_transfer = c.choice("growth.field_transfer", {"project", "carry"}) == "carry" ? FieldTransfer::Carry
                                                                                         : FieldTransfer::Project;
  if (c.has("growth.hold"))
    o.growth_hold = c.choice("growth.hold", {"old_segments", "total_opening"}) == "total_opening"
                        ? GrowthHold::TotalOpening
                        : GrowthHold::OldSegments;
  if (c.has("path.control"))
    o.control = c.choice("path.control", {"crack_opening", "displacement"}) == "displacement"
                    ? PathControl::Displacement
                    : PathControl::CrackOpening;
  if (c.has("path.zone_control")) {
    o.zone_control = c.choice("path.zone_control", {"fallback", "off"}) == "off" ? ZoneControl::Off : ZoneControl::Fallback;
  }
  opt(c, "path.energy_tolerance", o.energy_tolerance, Range::positive());
  if (c.has("path.jump"))
    o.jump = c.choice("path.jump", {"relax", "fail"}) == "fail" ? JumpFallback::Fail : JumpFallback::Relax;
  opt(c, "path.relaxation_ratio", o.relaxation_ratio, Range::closed(1.1, 1e3));
  opt(c, "path.max_relaxation_steps", o.max_relaxation_steps, Range::at_least(1));
  opt(c, "path.elastic_states", o.elastic_states, Range::at_least(1));
  opt(c, "path.opening_increment", o.opening_increment, Range::positive());
  opt(c, "path.min_opening_increment", o.min_opening_increment, Range::positive());
  opt(c, "path.max_opening_increment", o.max_opening_increment, Range::positive());
  opt(c, "path.strain_increment", o.strain_increment, Range::positive());
  opt(c, "path.min_strain_increment", o.min_strain_increment, Range::positive());
  opt(c, "path.max_strain_increment", o.max_strain_increment, Range::positive());
  opt(c, "path.step_growth", o.step_growth, Range::closed(1.0, 4.0));
  opt(c, "path.easy_iterations", o.easy_iterations, Range::at_least(0));
  opt(c, "path.max_steps", o.max_steps, Range::at_least(1));
  opt(c, "path.max_strain", o.max_strain, Range::positive());
  if (curve_end_strain && o.max_strain < *curve_end_strain)
    c.fail("path.max_strain", fmt::format("{} is below the strain grid's end {}: the curves would not cover the grid "
                                          "(leave it out to stop at the grid's end)",
                                          o.max_strain, *curve_end_strain));
  opt(c, "path.separation_fraction", o.separation_fraction, Range::open(0.0, 1.0));
  opt(c, "newton.max_iterations", o.max_iterations, Range::at_least(1));
  opt(c, "newton.line_search_halvings", o.line_search_halvings, Range::closed(0, 30));
  opt(c, "newton.tolerance", o.tolerance, Range::open(0.0, 1.0));
  opt(c, "newton.krylov_iterations", o.krylov_iterations, Range::closed(0, 200));
  // Consistency between keys.
  if (o.min_opening_increment > o.opening_increment)
    c.fail("path.min_opening_increment", "must not exceed path.opening_increment");
  if (o.max_opening_increment < o.opening_increment)
    c.fail("path.max_opening_increment", "must not be below path.opening_increment");
  if (o.min_strain_increment > o.strain_increment)
    c.fail("path.min_strain_increment", "must not exceed path.strain_increment");
  if (o.max_strain_increment < o.strain_increment)
    c.fail("path.max_strain_increment", "must not be below path.strain_increment");
  return o;
}

CellMaterial read_cell_material(const Config& m) {
  CellMaterial r;
  r.elastic.youngs_modulus_Pa = m.number("youngs_modulus_Pa", Range::positive());
  r.elastic.poissons_ratio = m.number("poissons_ratio", Range{-1.0, 0.5, true, true});
  r.tensile_strength_Pa = m.number("tensile_strength_Pa", Range::positive());
  r.fracture_energy_J_m2 = m.number("fracture_energy_J_m2", Range::positive());
  return r;
}

}  // namespace uhpc::micro
