#include "materials/afc.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Eigenvalues>

#include "materials/afc_strength.hpp"
#include "materials/point_driver.hpp"
#include "materials/principal_stress_limit.hpp"

namespace uhpc::macro {

namespace {

// The stress with its positive (tensile) principal values multiplied by `factor` in [0, 1], the
// negative ones kept (the split of eq. 21): sigma - (1 - factor) sum over l_i > 0 of l_i p_i p_i^T, so the
// compressive part is not touched by the round-off of a reconstruction. Eigen's closed-form 3x3
// solver: no allocation, no division.
Mat3 scale_tensile_part(const Mat3& stress, double factor) {
  if (factor == 1.0) return stress;
  Eigen::SelfAdjointEigenSolver<Mat3> es;
  es.computeDirect(stress);
  const Eigen::Vector3d lam = es.eigenvalues();
  Mat3 out = stress;
  for (int i = 0; i < 3; ++i)
    if (lam[i] > 0.0) {
      const Eigen::Vector3d p = es.eigenvectors().col(i);
      out -= ((1.0 - factor) * lam[i]) * (p * p.transpose());
    }
  return out;
}

// The largest principal value of the strain increment over dt, 0 when nothing stretches.
double largest_principal_rate(const Mat3& de, double dt) {
  if (!(dt > 0.0)) return 0.0;
  Eigen::SelfAdjointEigenSolver<Mat3> es;
  es.computeDirect(de, Eigen::EigenvaluesOnly);
  return std::max(es.eigenvalues()[2], 0.0) / dt;
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
  require(std::isfinite(p.options.crack_band_reference_size_m) && p.options.crack_band_reference_size_m > 0,
          "crack_band_reference_size_m must be finite and > 0");
  require(std::isfinite(p.options.crack_band_width_spacings) && p.options.crack_band_width_spacings >= 1,
          "crack_band_width_spacings must be finite and >= 1");
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
  require(p.options.principal_stress_limit == PrincipalStressLimit::Off ||
              p.options.tensile_degradation == TensileDegradation::Cutoff,
          "principal_stress_limit needs tensile_degradation = cutoff (the split already degrades the tension)");
  principal_limit_ = p.options.principal_stress_limit == PrincipalStressLimit::Tmax ? p.Tmax_Pa
                                                                                    : afc_uniaxial_tensile_strength(p);
  require(!p.options.crack_band_strength_reduction || (p.options.sdel_regularization == SdelRegularization::CrackBand &&
                                                       p.options.tensile_degradation == TensileDegradation::Cutoff),
          "crack_band_strength_reduction needs sdel_regularization = crack_band with tensile_degradation = cutoff");
  if (p.options.sdel_regularization == SdelRegularization::CrackBand &&
      p.options.tensile_degradation == TensileDegradation::Cutoff && p.options.tensile_damage == TensileDamage::Sdel) {
    track_tensile_work_ = true;
    reduce_band_strength_ = p.options.crack_band_strength_reduction;
    build_crack_band_curve();
    if (reduce_band_strength_) build_band_strength_table();
  }
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

double AfcMaterial::effective_tensile_strain(const Mat3& driver_stress) const {
  if (driver_stress.isZero(0.0)) return 0.0;
  Eigen::SelfAdjointEigenSolver<Mat3> es;
  es.computeDirect(driver_stress, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d lam = es.eigenvalues();
  double plus[3], trace = 0.0;
  for (int i = 0; i < 3; ++i) trace += plus[i] = std::max(lam[i], 0.0);
  if (trace == 0.0) return 0.0;
  // eps+ = C^-1 : sigma+ = ((1 + nu) sigma+ - nu tr(sigma+) I) / E, in the principal frame.
  const double K = hydro_.elastic_bulk_modulus(), G = p_.shear_modulus_Pa;
  const double E = 9.0 * K * G / (3.0 * K + G), nu = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double e = ((1.0 + nu) * plus[i] - nu * trace) / E;
    if (e > 0.0) sum += e * e;
  }
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

double AfcMaterial::crack_band_damage(double scaled_tensile_work) const {
  // The reference curve: d+ against the tensile work, from the onset (work 0) to failure (d+ = 1).
  const auto& w = band_.work;
  if (!(scaled_tensile_work > 0.0)) return 0.0;
  if (scaled_tensile_work >= w.back()) return 1.0;
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(w.begin(), w.end(), scaled_tensile_work) - w.begin());
  if (k == 0) return band_.onset;
  const double t = (scaled_tensile_work - w[k - 1]) / (w[k] - w[k - 1]);
  const double step = (1.0 - band_.onset) / static_cast<double>(kBandPoints - 1);
  return band_.onset + step * (static_cast<double>(k - 1) + t);
}

void AfcMaterial::build_crack_band_curve() {
  // The reference: the same law with the paper's lambda at h = l_ref (so SDEL(l_ref / l_mac)), driven in
  // quasi-static uniaxial stress (F = 1, no DIF) to full damage. Its tensile work is recorded against d+
  // from the onset of tensile yielding (the peak: before it the cutoff coupling dissipates nothing) and
  // resampled on kBandPoints values of d+, evenly spaced from the onset to 1.
  AfcParams ref = p_;
  ref.options.sdel_regularization = SdelRegularization::Lambda;
  ref.options.crack_band_strength_reduction = false;  // the reference holds its own band
  ref.options.tensile_rate = TensileRate::Off;
  ref.options.rate_factor_floor = 1.0;  // F = 1 at the driver's slow rate, whatever floor the case sets
  const double l_ref = p_.options.crack_band_reference_size_m;
  AfcMaterial reference(ref);
  reference.track_tensile_work_ = true;
  PointDriver<AfcMaterial> pt(reference, l_ref);
  std::vector<double> d, w;  // from the onset on (construction only)
  const double de = 1e-7, dt = 1e3;  // a rate far below edot0: F = its floor, 1 (above)
  for (int i = 0; i < 1000000 && pt.state().d_plus < 1.0; ++i) {
    const double booked = pt.state().plastic_work + pt.state().opening_work;
    pt.uniaxial_stress_step(de, dt);
    // The onset is the first step that yields (its work may be a round-off below 0: the curve starts at
    // 0 and never falls).
    if (d.empty() && !(pt.state().plastic_work + pt.state().opening_work > booked)) continue;
    const double work = std::max(pt.state().tensile_work, w.empty() ? 0.0 : w.back());
    if (d.empty()) {
      d.push_back(pt.state().d_plus);
      w.push_back(0.0);
    } else if (pt.state().d_plus > d.back()) {
      d.push_back(pt.state().d_plus);
      w.push_back(work);
    } else {
      w.back() = work;  // the same d+: the work of the step goes with it
    }
  }
  require(!d.empty() && d.back() >= 1.0 && d.size() >= 2,
          "sdel_regularization crack_band: the reference point does not fail in uniaxial tension");
  band_.onset = d.front();
  for (int j = 0; j < kBandPoints; ++j) {
    const double target = band_.onset + (1.0 - band_.onset) * j / (kBandPoints - 1);
    const std::size_t k = static_cast<std::size_t>(std::lower_bound(d.begin(), d.end(), target) - d.begin());
    if (k == 0) {
      band_.work[j] = 0.0;
    } else if (k >= d.size()) {
      band_.work[j] = w.back();
    } else {
      const double t = (target - d[k - 1]) / (d[k] - d[k - 1]);
      band_.work[j] = w[k - 1] + t * (w[k] - w[k - 1]);
    }
  }
  band_.work[0] = 0.0;
  for (int j = 1; j < kBandPoints; ++j) band_.work[j] = std::max(band_.work[j], band_.work[j - 1]);
}

std::pair<double, double> AfcMaterial::uniaxial_peak(double tmax_scale) const {
  const double K = hydro_.elastic_bulk_modulus(), G = p_.shear_modulus_Pa, E = 9.0 * K * G / (3.0 * K + G);
  const double ft = afc_uniaxial_tensile_strength(p_), a = ft / (1.0 - ft / (3.0 * p_.Tmax_Pa));  // a = S(0)
  const double l_ref = p_.options.crack_band_reference_size_m;
  const auto damage = [&](double e) { return std::min(sdel_damage(e, l_ref), band_.onset); };
  const auto excess = [&](double e) {  // E e less the limit at the d+ of e: rises with e
    const double T = tmax_scale * p_.Tmax_Pa * (1.0 - damage(e));
    return E * e - (T > 0.0 ? a / (1.0 + a / (3.0 * T)) : 0.0);
  };
  double lo = 0.0, hi = 2.0 * afc_uniaxial_tensile_strength(p_) / E;
  for (int i = 0; i < 200; ++i) (excess(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
  return {hi, damage(hi)};
}

void AfcMaterial::build_band_strength_table() {
  const double K = hydro_.elastic_bulk_modulus(), G = p_.shear_modulus_Pa, E = 9.0 * K * G / (3.0 * K + G);
  const auto peak_energy = [&](double scale) {
    const double e = uniaxial_peak(scale).first;
    return 0.5 * E * e * e;
  };
  const double holding = peak_energy(1.0);
  for (int k = 0; k < kStrengthPoints; ++k) {
    const double ratio = std::pow(kStrengthRange, static_cast<double>(k) / (kStrengthPoints - 1));  // w / w_lim
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 100; ++i) (peak_energy(0.5 * (lo + hi)) < holding / ratio ? lo : hi) = 0.5 * (lo + hi);
    strength_.scale[k] = lo;
    strength_.peak_damage[k] = uniaxial_peak(lo).second;
  }
}

AfcMaterial::BandStrength AfcMaterial::band_strength(double band_width_m) const {
  const double w_lim = kHoldingWidth * p_.options.crack_band_reference_size_m;
  if (!reduce_band_strength_ || !(band_width_m > w_lim)) return {1.0, band_.onset};
  const double x = std::log(band_width_m / w_lim) / std::log(kStrengthRange) * (kStrengthPoints - 1);
  if (!(x < kStrengthPoints - 1)) return {strength_.scale.back(), strength_.peak_damage.back()};
  const int k = static_cast<int>(x);
  const double t = x - k;
  return {strength_.scale[k] + t * (strength_.scale[k + 1] - strength_.scale[k]),
          strength_.peak_damage[k] + t * (strength_.peak_damage[k + 1] - strength_.peak_damage[k])};
}

void AfcMaterial::update(State& st, const MaterialStep& step) const {
  const AfcOptions& o = p_.options;
  const bool split = o.tensile_degradation == TensileDegradation::Split;
  const Mat3& de = step.strain_increment;
  const Mat3 dev_increment = 2.0 * p_.shear_modulus_Pa * deviator(de);
  const double mu = step.density_ratio - 1.0;
  // The strain the hydrostat reads: mu itself, less the permanent opening with OpenedVolume::Permanent.
  double mu_h = mu - st.opening_strain;
  const double F = afc_rate_factor(effective_deviatoric_rate(de, step.dt_s), p_);
  const bool rate = o.tensile_rate != TensileRate::Off;
  // The tensile DIF of this step's largest principal strain rate (used when the tensile strain grows).
  const double dif_now = rate ? afc_tensile_dif(largest_principal_rate(de, step.dt_s), p_) : 1.0;
  // State::tensile_work (SdelRegularization::CrackBand): the start of the step's stress and free energy
  // per reference volume (V_old / V0 = 1 / (rho_new / rho0 exp(tr d eps)), the solver's volume update).
  const Mat3 stress_old = track_tensile_work_ ? st.stress : Mat3::Zero();
  const double psi_old = track_tensile_work_ ? stored_energy(st) / (step.density_ratio * std::exp(de.trace())) : 0.0;

  // 1. Hydrostat history.
  const double mu_max_old = st.mu_max;
  st.mu_max = std::max(st.mu_max, mu_h);
  double P_uncut = hydro_.uncut_pressure(mu_h, st.mu_max);
  const double mu_p = hydro_.crushing_strain(st.mu_max);
  const double dmu_p = mu_p - st.crushing_strain;
  st.crushing_work += hydro_.crushing_dissipation(mu_max_old, st.mu_max, st.opening_strain);

  // The crack band's strength reduction of this point's band (none: Tmax as it is, the reference's onset).
  const BandStrength band = reduce_band_strength_ ? band_strength(band_width(step.spacing_m)) : BandStrength{1.0, band_.onset};

  // 2. Tensile damage (never decreasing: kappa and d+ are history maxima).
  bool crack_band_growing = false;  // the split's CrackBand and kappa grew in this step
  if (o.tensile_damage == TensileDamage::Sdel) {
    const double kappa_old = st.tensile_strain_max;
    double e;
    if (p_.strain_measure == TensileStrainMeasure::EffectiveTensile) {
      // The driver: no tensile limit; on the compressive side the deviator yields onto eq. 33 as the
      // effective stress does, so plastic flow in compression is not counted as tension. Its pressure
      // reads the whole volumetric strain mu (a permanent opening is still tension to the driver, else a
      // point held at the cutoff could never damage further).
      const double P_driver = hydro_.uncut_pressure(mu, std::max(st.mu_max, mu));
      Mat3 s_bar = deviator(st.driver_stress) + dev_increment;
      if (P_driver >= 0.0) {
        const double S = afc_strength_compression(P_driver, st.d_minus, F, p_);
        const double q = std::sqrt(1.5 * s_bar.cwiseProduct(s_bar).sum());
        if (q > S) s_bar *= S / q;
      }
      st.driver_stress = s_bar - P_driver * Mat3::Identity();
      e = effective_tensile_strain(st.driver_stress);
    } else {
      st.strain += de;
      e = equivalent_tensile_strain(st.strain);
    }
    if (!rate) {
      st.tensile_strain_max = std::max(st.tensile_strain_max, e);
    } else if (e > st.tensile_strain_reached) {
      // With the tensile DIF, kappa grows by each new increment of the strain history over the DIF of
      // the step that made it, and the DIF is held while the strain does not grow: a step with no
      // stretch (rate 0, DIF 1) neither jumps kappa to e nor drops the cutoff.
      st.tensile_dif = dif_now;
      st.tensile_strain_max += (e - st.tensile_strain_reached) / dif_now;
      st.tensile_strain_reached = e;
    }
    if (o.sdel_regularization == SdelRegularization::Lambda) {
      st.d_plus = std::max(st.d_plus, sdel_damage(st.tensile_strain_max, step.spacing_m));
    } else {
      if (!(step.spacing_m > 0.0) || !std::isfinite(step.spacing_m))
        throw std::invalid_argument("AfcMaterial: the particle spacing h_I must be > 0 for the SDEL");
      if (split) {
        // The split's crack band (below, once the effective stress is known), only while kappa grows:
        // with n_b h > l_ref a falling stress would raise the band strain, and unloading must not damage.
        crack_band_growing = st.tensile_strain_max > kappa_old;
      } else {
        // The cutoff coupling's crack band (afc_params.hpp): up to the reference's onset of tensile
        // yielding d+ is the reference SDEL of kappa (nothing is dissipated yet); past it d+ follows the
        // tensile work per volume scaled by n_b h / l_ref along the reference's own curve (and by 1 / DIF^2
        // with the tensile DIF: the lambda law stretches its curve and raises its cutoff by DIF, which
        // dissipates DIF^2 the energy), the work of the steps before (explicit: solving for this step's
        // own work at its fixed strain increment is unstable, a falling limit at fixed strain releases
        // several times what it releases on the equilibrium path, and substeps at fixed strain are too).
        const double energy_scale = band_width(step.spacing_m) / o.crack_band_reference_size_m / (st.tensile_dif * st.tensile_dif);
        // A band with its strength reduced peaks at a lower d+ than the reference's onset: its curve starts
        // at its own peak, from the same work, so that d+ never jumps to the onset.
        const double peak = band.peak_damage;
        const double before_onset = std::min(sdel_damage(st.tensile_strain_max, o.crack_band_reference_size_m), peak);
        double after_onset = crack_band_damage(st.tensile_work * energy_scale);
        if (after_onset > 0.0 && peak < band_.onset)
          after_onset = peak + (1.0 - peak) * (after_onset - band_.onset) / (1.0 - band_.onset);
        st.d_plus = std::max(st.d_plus, std::max(before_onset, after_onset));
      }
    }
  } else if (rate) {
    st.tensile_dif = dif_now;  // no damage to hold it for: the cutoff follows the rate
  }
  // The factor on the tensile limits: the DIF (1 without the rate option) and, with the crack band's
  // strength reduction, the band's factor on Tmax (1 for a band the law holds).
  const double dif = st.tensile_dif * band.tmax_scale;

  // 3. Effective stress: pressure with the cutoff, deviator returned at fixed pressure onto S. With the
  // split, d+ acts on the stress handed to the solver (5.), not on these limits.
  const double d_plus_in_limits = split ? 0.0 : st.d_plus;
  const double T = dif * p_.Tmax_Pa * (1.0 - d_plus_in_limits);
  const bool permanent = o.opened_volume == OpenedVolume::Permanent;
  if (permanent && P_uncut < -T) {
    // Opening past the cutoff is kept: the hydrostat is moved to where its line meets -T, and the work
    // of the pressure -T over the opened volume is dissipated (per reference volume, -P dV / V0).
    const double mu_cut = st.mu_max - (hydro_.loading_pressure(st.mu_max) + T) / hydro_.unloading_modulus(st.mu_max);
    const double opened = mu_h - mu_cut;  // < 0
    st.opening_strain += opened;
    st.opening_work += -T * opened / ((1.0 + mu) * (1.0 + mu - opened));  // T (V - V_cut) / V0, exact
    mu_h = mu_cut;
    P_uncut = -T;
  }
  const double P = std::max(P_uncut, -T);
  Mat3 s = deviator(st.effective_stress) + dev_increment;
  const double q_trial = std::sqrt(1.5 * s.cwiseProduct(s).sum());
  // The branch follows the side of the hydrostat before its cutoff (afc_strength.hpp): at d+ = 1 an
  // expanded point has P = 0 but is open, and eq. 35's limit there is S = 0.
  // With the permanent opening a point held at a zero cutoff (d+ = 1) sits at P_uncut = 0 and is open.
  const bool open_side = P_uncut < 0.0 || (permanent && P_uncut <= -T);
  double S = open_side ? afc_strength_tension(P, st.d_minus, d_plus_in_limits, F, p_, dif)
                       : afc_strength_compression(P, st.d_minus, F, p_);
  if (o.lode == LodeDependence::WillamWarnke) {
    // r >= psi >= 0.5: below psi S no deviator can yield, so the invariant is only computed above it.
    const double psi = lode_psi(P, st.d_minus, F, p_);
    if (q_trial > psi * S) S *= willam_warnke_factor(lode_cos3theta(s), psi);
  }
  double dep = 0.0;
  st.deviatoric_return = 1.0;
  st.at_tensile_cutoff = P > P_uncut || (permanent && P_uncut <= -T);
  if (q_trial > S) {
    st.deviatoric_return = S / q_trial;
    dep = (q_trial - S) / (3.0 * p_.shear_modulus_Pa);
    s *= S / q_trial;
    st.plastic_strain += dep;
    st.plastic_work += S * dep / step.density_ratio;  // s : d eps_p = S d eps_p per current volume
  }
  const double plastic_before_limit = st.plastic_work;
  if (o.principal_stress_limit != PrincipalStressLimit::Off) limit_principal_stress(st, s, P, dif, step.density_ratio);
  // A tensile mechanism acted in this step: eq. 35's return, the cutoff or the principal-stress limit.
  const bool tensile_action = (open_side && dep > 0.0) || st.at_tensile_cutoff || st.plastic_work > plastic_before_limit;

  // 4. Compressive damage (eq. 36), only under compression; d- enters the next step's strength. The
  // principal-stress limit is a tensile mechanism (its damage is d+) and does not add to d-.
  if (P > 0.0) {
    const double inc = dep / std::max(P * p_.D1_1_Pa, o.damage_eps_min) + dmu_p / (1.5 * p_.C9);
    st.d_minus = std::min(1.0, st.d_minus + inc);
  }
  st.crushing_strain = mu_p;
  st.mu = mu_h;
  st.effective_stress = s - P * Mat3::Identity();

  // The split's crack band: (1 - d+) sigma_e(kappa) must be the reference band's (1 - d_ref(u)) sigma_e(u).
  // The effective stress does not depend on d+ (its limits are the undamaged ones), so its measure e_e
  // is this step's: sigma_e grows with the strain up to e_e and is held at AFC's strength beyond, so
  // sigma_e(u) / sigma_e(kappa) = m(u) / e_e with m(u) = min(u, e_e), and the elastic part of the
  // point is (1 - d_ref(u)) m(u). The band's strain u = e_el + (kappa - e_el) n_b h / l_ref is then the
  // root of f(u) = u - (1 - r) (1 - d_ref(u)) m(u) - r kappa, r = n_b h / l_ref, solved here rather than
  // lagged by a step: the lag's fixed-point map is not a contraction on the steep part of the SDEL.
  // For r <= 1, f rises (f' >= r) from f(r kappa) <= 0 to f(kappa) >= 0: one root, by bisection. For
  // r > 1 the bracket is [kappa, r kappa] and a steep softening can have several roots (the point
  // snaps back: docs/physics.md section 4.4).
  if (split && crack_band_growing) {
    const double kappa = st.tensile_strain_max, r = band_width(step.spacing_m) / o.crack_band_reference_size_m;
    const double e_e = effective_tensile_strain(st.effective_stress) / st.tensile_dif;
    const auto elastic = [&](double u) {
      return (1.0 - sdel_damage(u, o.crack_band_reference_size_m)) * std::min(u, e_e);
    };
    double lo = std::min(r, 1.0) * kappa, hi = std::max(r, 1.0) * kappa;
    for (int i = 0; i < 60 && hi - lo > 1e-12 * kappa; ++i) {
      const double mid = 0.5 * (lo + hi);
      (mid - (1.0 - r) * elastic(mid) - r * kappa < 0.0 ? lo : hi) = mid;
    }
    const double u = 0.5 * (lo + hi), d_ref = sdel_damage(u, o.crack_band_reference_size_m);
    const double ratio = e_e > 0.0 ? std::min(u, e_e) / e_e : 1.0;
    st.d_plus = std::max(st.d_plus, std::clamp(1.0 - (1.0 - d_ref) * ratio, 0.0, 1.0));
  }

  // 5. The stress the solver integrates (eq. 21): the tensile principal part degraded by 1 - d+.
  st.stress = split ? scale_tensile_part(st.effective_stress, 1.0 - st.d_plus) : st.effective_stress;

  // The tensile work: what a step in which a tensile mechanism acted dissipated, its stress work less the
  // change of the free energy (per reference volume, the trapezoid on the step). Booked plastic and
  // opening work alone miss the energy a falling cutoff or strength releases at a fixed strain, which in
  // a laterally held point is most of it. Steps with no tensile mechanism are skipped, so the round-off
  // of elastic steps does not add up.
  if (track_tensile_work_ && tensile_action) {
    const double J_new = 1.0 / step.density_ratio, J_old = J_new * std::exp(-de.trace());
    const double work = 0.5 * (stress_old + st.stress).cwiseProduct(de).sum() * 0.5 * (J_old + J_new);
    st.tensile_work += work - (stored_energy(st) * J_new - psi_old);
  }
}

void AfcMaterial::limit_principal_stress(State& st, Mat3& s, double P, double dif, double density_ratio) const {
  // sigma_1 = s_1 - P <= DIF T_R (1 - d+). |s_1| <= 2 q / 3, so below that nothing is computed.
  const double limit = dif * principal_limit_ * (1.0 - st.d_plus);
  const double c = std::max(limit + P, 0.0);  // >= 0 under the cutoff coupling (P >= -DIF Tmax (1 - d+))
  const double norm2 = s.cwiseProduct(s).sum();
  if (std::sqrt(2.0 / 3.0 * norm2) <= c) return;
  const Mat3 s_new = limit_principal_deviator(s, c);
  const Mat3 ds = s - s_new;  // 2G d eps_p
  const double ds2 = ds.cwiseProduct(ds).sum();
  if (!(ds2 > 0.0)) return;
  const double G = p_.shear_modulus_Pa;
  st.plastic_strain += std::sqrt(2.0 / 3.0 * ds2) / (2.0 * G);
  st.plastic_work += s_new.cwiseProduct(ds).sum() / (2.0 * G) / density_ratio;  // per reference volume
  // The NSNI gradient follows a radial return's factor (Moduli::deviatoric_return); this return is not
  // radial, and the ratio of the deviators' norms stands for it.
  st.deviatoric_return *= std::sqrt(s_new.cwiseProduct(s_new).sum() / norm2);
  s = s_new;
}

void AfcMaterial::rotate(State& st, const Mat3& R) const {
  st.stress = R * st.stress * R.transpose();
  st.effective_stress = R * st.effective_stress * R.transpose();
  if (p_.strain_measure == TensileStrainMeasure::EffectiveTensile)
    st.driver_stress = R * st.driver_stress * R.transpose();
}

bool AfcMaterial::stress_free(const State& st, double density_ratio) const {
  if (!(st.d_plus >= 1.0)) return false;
  if (p_.options.opened_volume == OpenedVolume::Permanent) {
    // Open while the last update held it at the (zero) cutoff: its hydrostat read no compression.
    if (!st.at_tensile_cutoff) return false;
  } else if (!(density_ratio < 1.0)) {
    return false;
  }
  if (p_.options.tensile_degradation == TensileDegradation::Cutoff) return true;
  // The split hands on the compressive principal stresses: free only if the effective stress has none.
  Eigen::SelfAdjointEigenSolver<Mat3> es;
  es.computeDirect(st.effective_stress, Eigen::EigenvaluesOnly);
  return es.eigenvalues()[0] >= 0.0;
}

double AfcMaterial::stored_energy(const State& st) const {
  return half_compliance_product(st.stress, st.effective_stress, hydro_.unloading_modulus(st.mu_max),
                                 p_.shear_modulus_Pa);
}

double AfcMaterial::wave_speed(const State& state, double density_ratio) const {
  // A stress-free point (fully failed and open: no tangent) resists nothing until it closes back to
  // rho0; its speed is that of the closed material. At the current density it would grow as
  // sqrt(V / V0) with a shear modulus that no longer acts, and expanding ejecta (V up to 1e3 V0) would
  // collapse the stable step.
  double mu = density_ratio - 1.0 - state.opening_strain;  // the strain the hydrostat reads
  if (stress_free(state, density_ratio)) {
    density_ratio = 1.0;
    mu = 0.0;
  }
  double slope = hydro_.slope(mu, state.mu_max);
  if (p_.options.wave_speed_from_unloading_modulus)
    slope = std::max(slope, hydro_.unloading_modulus(state.mu_max));
  const double K = density_ratio * slope;  // rho dP/drho
  return std::sqrt((K + 4.0 / 3.0 * p_.shear_modulus_Pa) / (p_.density_kg_m3 * density_ratio));
}

Moduli AfcMaterial::moduli(const State& state) const {
  // The tangent of the hydrostat at the point's state: the loading slope on the curve (the crushing
  // slope while crushing), K_u on the unloading line. Along the deviator 0: S depends on P, d- and the
  // rate, not on the plastic flow itself (its change with the pressure gradient is neglected).
  const double bulk = (1.0 + state.mu + state.opening_strain) * hydro_.slope(state.mu, state.mu_max);  // rho dP/drho
  const double tension = p_.options.tensile_degradation == TensileDegradation::Split ? 1.0 - state.d_plus : 1.0;
  return {bulk, p_.shear_modulus_Pa, state.deviatoric_return, 0.0, state.at_tensile_cutoff, tension};
}

void AfcMaterial::output_values(const State& state, double* out) const {
  out[0] = state.d_plus;
  out[1] = state.d_minus;
  out[2] = state.plastic_strain;
  out[3] = state.tensile_strain_max;
}

}  // namespace uhpc::macro
