#include "run_warnings.hpp"

#include <fmt/format.h>

#include <cmath>

namespace uhpc::macro {

double impact_point_spacing(const CaseSettings& settings) {
  const TargetSettings& t = settings.target;
  return t.shape == TargetSettings::Shape::Box ? t.box_spacing_m
                                               : disc_spacing_at(t.disc, std::abs(settings.projectile.offset_m));
}

std::vector<RunWarning> warnings_before_run(const CaseSettings& settings) {
  std::vector<RunWarning> w;
  const TargetSettings& t = settings.target;
  const double h = impact_point_spacing(settings);
  const double across = t.thickness_m() / h;
  if (across < kMinParticlesThroughThickness)
    w.push_back({"thin_target", fmt::format("the target is {:.1f} particles thick at the impact point ({:.2f} mm at "
                                            "{:.2f} mm spacing), fewer than {:g}: its penetration is not resolved",
                                            across, t.thickness_m() * 1e3, h * 1e3, kMinParticlesThroughThickness)});
  if (settings.solver.energy_error_limit == 0.0)
    w.push_back({"energy_check_off", "solver.energy_error_limit = 0: the energy balance is not checked, an unstable "
                                     "run goes on (read energy.balance_error in result.json)"});
  return w;
}

std::vector<RunWarning> warnings_for_material(const MaterialSet& material, const CaseSettings& settings) {
  std::vector<RunWarning> w;
  const auto* afc = std::get_if<MaterialBlock<AfcMaterial>>(&material);
  if (!afc) return w;
  const AfcOptions& o = afc->law.params().options;
  if (o.sdel_regularization != SdelRegularization::CrackBand || o.tensile_damage == TensileDamage::Off) return w;
  const double spacing_m = impact_point_spacing(settings), band = afc->law.band_width(spacing_m);
  // With the strength reduction a wider band is held (its strength lowered) up to the reduction's range.
  const double factor = o.crack_band_strength_reduction ? AfcMaterial::kStrengthRange * AfcMaterial::kHoldingWidth
                        : o.tensile_degradation == TensileDegradation::Split ? kCrackBandLimitSplit
                                                                              : kCrackBandLimitCutoff;
  const double limit = factor * o.crack_band_reference_size_m;
  if (band > limit)
    w.push_back({"crack_band_too_wide",
                 fmt::format("the crack band at the impact point is {:.2f} mm wide ({:g} x {:.2f} mm), past the {:.2f} mm "
                             "({:g} l_ref) up to which a point dissipates G_ref: it snaps back and dissipates more",
                             band * 1e3, o.crack_band_width_spacings, spacing_m * 1e3, limit * 1e3, factor)});
  return w;
}

WallTimeEstimate estimate_wall_time(std::size_t particles, double remaining_s, double first_step_s, int threads) {
  const double steps = remaining_s / first_step_s;
  const double seconds = static_cast<double>(particles) * steps / (kParticleStepsPerThreadPerSecond * threads);
  return {seconds, fmt::format("estimated wall time up to the end time about {:.0f} min ({:.3g} steps of {} particles "
                               "on {} thread(s) at about {:.2g} particle-steps/s a thread; a decided shot stops sooner)",
                               seconds / 60.0, steps, particles, threads, kParticleStepsPerThreadPerSecond)};
}

std::vector<RunWarning> warnings_after_run(const EnergyLedger& e) {
  std::vector<RunWarning> w;
  const double lost = e.kinetic_initial - e.kinetic_sphere;
  if (!(lost > 0.0)) return w;
  const double contact = e.contact / lost, stabilization = e.stabilization_dissipated() / lost;
  if (contact + stabilization > kMaxNumericalShare)
    w.push_back({"numerical_dissipation",
                 fmt::format("the contact ({:.0f} %) and the NSNI stabilization ({:.0f} %) took {:.0f} % of the sphere's "
                             "lost kinetic energy, more than {:.0f} %: the result depends on the discretization more "
                             "than on the material",
                             100 * contact, 100 * stabilization, 100 * (contact + stabilization), 100 * kMaxNumericalShare)});
  if (stabilization < kNegativeStabilizationShare)
    w.push_back({"negative_stabilization",
                 fmt::format("the NSNI stabilization gave back {:.1f} % of the sphere's lost kinetic energy (negative "
                             "dissipation): the stabilization is not dissipative here",
                             -100 * stabilization)});
  return w;
}

nlohmann::json warnings_json(const std::vector<RunWarning>& warnings) {
  nlohmann::json j = nlohmann::json::array();
  for (const RunWarning& r : warnings) j.push_back({{"code", r.code}, {"message", r.message}});
  return j;
}

}  // namespace uhpc::macro
