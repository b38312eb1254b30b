#include "materials/afc.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "materials/afc_strength.hpp"

namespace uhpc::macro {

namespace {

// The stress with its positive (tensile) principal values multiplied by `factor`, the negative ones
// kept (the split of eq. 21). Eigen's closed-form 3x3 solver: no allocation.
Mat3 scale_tensile_part(const Mat3& stress, double factor) {
  Eigen::SelfAdjointEigenSolver<Mat3> es;
  es.computeDirect(stress);
  Eigen::Vector3d lam = es.eigenvalues();
  for (int i = 0; i < 3; ++i)
    if (lam[i] > 0.0) lam[i] *= factor;
  return es.eigenvectors() * lam.asDiagonal() * es.eigenvectors().transpose();
}

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("AfcMaterial: ") + what);
}

}  // namespace

AfcMaterial::AfcMaterial(const AfcParams& params) : p_(params), hydro_(params) {
  const AfcParams& p = p_;
  require(p.density_kg_m3 > 0 && p.shear_modulus_Pa > 0, "density and shear modulus must be > 0");
  require(p.C2_Pa > 0 && p.C1_Pa > p.C2_Pa, "need C1 > C2 > 0 (C1 - C2 is the strength at P = 0)");
  require(p.C3 >= 0 && p.C4 >= 0 && p.C5_Pa > 0, "need C3 >= 0, C4 >= 0, C5 > 0");
  require(p.C6_Pa > 0 && p.C7 > 0 && p.C9 > p.C7 && p.C8_Pa > 0, "need C6, C7, C8 > 0 and C9 > C7");
  require(p.D1_1_Pa > 0 && p.An_1_Pa > 0 && p.Tmax_Pa > 0, "D1, An and Tmax must be > 0");
  require(p.reference_strain_rate_1_s > 0, "the reference strain rate must be > 0");
  require(p.sdel.a > 0 && p.sdel.A > 0 && p.sdel.nu > 0 && p.sdel.chi > 0 && p.l_mac_m > 0,
          "the SDEL constants and l_mac must be > 0");
  require(p.options.damage_eps_min > 0, "damage_eps_min must be > 0");
  require(std::isfinite(p.options.rate_factor_floor) && p.options.rate_factor_floor >= 0,
          "rate_factor_floor must be finite and >= 0");
  // The crushing curve must rise (a falling hydrostat has no sound speed) and stay below the unloading
  // lines (K_u >= K_e must bound its slope, else unloading would cross the loading curve).
  const double Ke = hydro_.elastic_bulk_modulus();
  for (int i = 0; i <= 256; ++i) {
    const double mu = p.C7 + (p.C9 - p.C7) * i / 256.0;
    const double s = hydro_.loading_slope(mu);
    require(s > 0, "the crushing curve C6 + K1 x + K2 x^2 + K3 x^3 must increase on [C7, C9]");
    require(s <= hydro_.unloading_modulus(mu) * (1 + 1e-12), "the crushing slope must not exceed the unloading modulus K_u");
  }
  require(p.C8_Pa >= Ke, "the locking modulus C8 must be >= K_e = C6 / C7 (K_u interpolates between them)");
}

double AfcMaterial::equivalent_tensile_strain(const Mat3& strain) const {
  Eigen::SelfAdjointEigenSolver<Mat3> es;
  es.computeDirect(strain, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d e = es.eigenvalues();  // ascending
  if (p_.strain_measure == TensileStrainMeasure::MaxPrincipal) return std::max(e[2], 0.0);
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) sum += e[i] > 0.0 ? e[i] * e[i] : 0.0;
  return std::sqrt(sum);
}

double AfcMaterial::sdel_damage(double kappa, double spacing_m) const {
  if (!(spacing_m > 0.0) || !std::isfinite(spacing_m))
    throw std::invalid_argument("AfcMaterial: the particle spacing h_I must be > 0 for the SDEL");
  const double lambda = spacing_m / p_.l_mac_m;
  const double d = p_.options.sdel_zero_anchored ? uhpc::sdel_damage_zero_anchored(lambda, kappa, p_.sdel)
                                                 : uhpc::sdel_damage(lambda, kappa, p_.sdel);
  return std::clamp(d, 0.0, 1.0);
}

void AfcMaterial::update(State& st, const MaterialStep& step) const {
  const AfcOptions& o = p_.options;
  const Mat3& de = step.strain_increment;
  const double G = p_.shear_modulus_Pa;
  const double mu = step.density_ratio - 1.0;

  // 1. Strain history and tensile damage (never decreasing: kappa and d+ are history maxima).
  st.strain += de;
  if (o.tensile_damage == TensileDamage::Sdel) {
    st.tensile_strain_max = std::max(st.tensile_strain_max, equivalent_tensile_strain(st.strain));
    st.d_plus = std::max(st.d_plus, sdel_damage(st.tensile_strain_max, step.spacing_m));
  }

  // 2. Hydrostat.
  const double mu_max_old = st.mu_max;
  st.mu_max = std::max(st.mu_max, mu);
  const double P_uncut = hydro_.uncut_pressure(mu, st.mu_max);
  const double P = std::max(P_uncut, -p_.Tmax_Pa * (1.0 - st.d_plus));
  const double mu_p = hydro_.crushing_strain(st.mu_max);
  const double dmu_p = mu_p - st.crushing_strain;
  st.dissipated += hydro_.crushing_dissipation(mu_max_old, st.mu_max);

  // 3. Deviator: elastic trial, radial return at fixed pressure onto S.
  Mat3 previous = st.stress;
  if (o.degrade_tensile_stress && st.tension_factor > 0.0 && st.tension_factor < 1.0)
    previous = scale_tensile_part(st.stress, 1.0 / st.tension_factor);  // the undegraded stress
  Mat3 s = deviator(previous) + 2.0 * G * deviator(de);
  const double q_trial = std::sqrt(1.5 * s.cwiseProduct(s).sum());
  const double F = afc_rate_factor(effective_deviatoric_rate(de, step.dt_s), p_);
  // The branch follows the side of the hydrostat before its cutoff (afc_strength.hpp): at d+ = 1 an
  // expanded point has P = 0 but is open, and eq. 35's limit there is S = 0.
  const double S = P_uncut < 0.0 ? afc_strength_tension(P, st.d_minus, st.d_plus, F, p_)
                                 : afc_strength_compression(P, st.d_minus, F, p_);
  double dep = 0.0;
  st.deviatoric_return = 1.0;
  st.at_tensile_cutoff = P > P_uncut;
  if (q_trial > S) {
    st.deviatoric_return = S / q_trial;
    dep = (q_trial - S) / (3.0 * G);
    s *= S / q_trial;
    st.plastic_strain += dep;
    st.dissipated += S * dep / step.density_ratio;  // s : d eps_p = S d eps_p per current volume
  }

  // 4. Compressive damage (eq. 36), only under compression; d- enters the next step's strength.
  if (P > 0.0) {
    const double inc = dep / std::max(P * p_.D1_1_Pa, o.damage_eps_min) + dmu_p / (1.5 * p_.C9);
    st.d_minus = std::min(1.0, st.d_minus + inc);
  }
  st.crushing_strain = mu_p;
  st.mu = mu;

  st.stress = s - P * Mat3::Identity();
  if (o.degrade_tensile_stress) {
    st.tension_factor = 1.0 - st.d_plus;
    st.stress = scale_tensile_part(st.stress, st.tension_factor);
  }
}

double AfcMaterial::wave_speed(const State& state, double density_ratio) const {
  // A stress-free point (fully failed and open: no tangent) resists nothing until it closes back to
  // rho0; its speed is that of the closed material. At the current density it would grow as
  // sqrt(V / V0) with a shear modulus that no longer acts, and expanding ejecta (V up to 1e3 V0) would
  // collapse the stable step.
  if (stress_free(state, density_ratio)) density_ratio = 1.0;
  const double mu = density_ratio - 1.0;
  double slope = hydro_.slope(mu, state.mu_max);
  if (p_.options.wave_speed_from_unloading_modulus)
    slope = std::max(slope, hydro_.unloading_modulus(state.mu_max));
  const double K = density_ratio * slope;  // rho dP/drho
  return std::sqrt((K + 4.0 / 3.0 * p_.shear_modulus_Pa) / (p_.density_kg_m3 * density_ratio));
}

Moduli AfcMaterial::moduli(const State& state) const {
  const double slope = std::max(hydro_.unloading_modulus(state.mu_max), hydro_.slope(state.mu, state.mu_max));
  // Along the deviator 0: S depends on P, d- and the rate, not on the plastic flow itself (its change
  // with the pressure gradient is neglected).
  return {(1.0 + state.mu) * slope, p_.shear_modulus_Pa, state.deviatoric_return, 0.0, state.at_tensile_cutoff};
}

void AfcMaterial::output_values(const State& state, double* out) const {
  out[0] = state.d_plus;
  out[1] = state.d_minus;
  out[2] = state.plastic_strain;
}

}  // namespace uhpc::macro
