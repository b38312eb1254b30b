#pragma once
// The AFC concrete model with SDEL tensile damage (docs/physics.md section 4; equations as implemented and
// every option in macro/README.md, "AFC concrete model"). One step at a particle, in this order:
//   1. hydrostat history: mu_h = rho/rho0 - 1 - mu_o (mu_o the permanent opening, 0 unless
//      OpenedVolume::Permanent), mu_max = max(mu_max, mu_h), the uncut pressure P_u (afc_hydrostat.hpp,
//      the curve or the unloading line without the tensile cutoff), the crushing strain mu_p and its
//      dissipation;
//   2. tensile damage: e = equivalent tensile strain by the handoff's measure, kappa = max(kappa, e)
//      (with AfcOptions::tensile_rate: kappa += (new growth of e) / DIF of that step, DIF held between),
//      d+ = max(d+, SDEL(lambda, kappa)), lambda = h_I / l_mac (h_I = MaterialStep::spacing_m); with
//      SdelRegularization::CrackBand (afc_params.hpp) the reference size's SDEL up to the reference's
//      onset of tensile yielding, past it d+ of the reference at the tensile work so far scaled by
//      h_I / l_ref (cutoff coupling), or the reference band's d+ at the same crack opening (split). The
//      default measure (EffectiveTensile) reads the driver stress sigma_bar: the same material with no
//      tensile limit (P from the whole rho/rho0 - 1, the deviator returned only on the compressive
//      side, onto eq. 33), so e is the norm of the positive principal strains of C^-1 : <sigma_bar>+:
//      zero in uniaxial compression, the axial strain in uniaxial tension (what the microcells were
//      fitted to), and rotated with the material (State::driver_stress is objective);
//   3. effective stress: T = DIF Tmax (1 - d+) with the cutoff coupling (default), DIF Tmax with the split;
//      with the permanent opening, a P_u below -T moves mu_o so that P_u = -T (the opened volume is
//      kept, its work T d(-mu_o) booked); P = max(P_u, -T); deviator: elastic trial s + 2G dev(d eps),
//      radial return at fixed pressure (no dilatancy) onto S(P, d-, T, F) (afc_strength.hpp), times
//      the Willam-Warnke factor r(theta, psi(P)) with the Lode option; F from this step's effective
//      deviatoric rate; d eps_p = (q_trial - S) / (3G); then, with the principal-stress limit, the
//      closest deviator with s_1 <= T_R (1 - d+) + P (principal_stress_limit.hpp);
//   4. d- += d eps_p / max(P D1, eps_min) + d mu_p / (1.5 C9) while P > 0 (eq. 36), clipped to 1;
//   5. the stress handed to the solver: sigma_e, or <sigma_e>- + (1 - d+) <sigma_e>+ with the split (eq. 21).
// d- enters the strength with its value at the start of the step (explicit), d+ with the new value.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "materials/afc_hydrostat.hpp"
#include "materials/afc_params.hpp"
#include "materials/material_step.hpp"

namespace uhpc::macro {

class AfcMaterial {
 public:
  struct State {
    // The stress handed to the solver (effective_stress itself with the cutoff coupling, its eq. 21
    // split with the split).
    Mat3 stress = Mat3::Zero();
    // The AFC stress before the split: hydrostat with its cutoff and the eq. 33/35 return (objective).
    Mat3 effective_stress = Mat3::Zero();
    // sigma_bar of the EffectiveTensile measure: the material without tensile limits (objective).
    Mat3 driver_stress = Mat3::Zero();
    // Sum of the strain increments D dt (Mazars and MaxPrincipal measures only). Kept as the earlier
    // option defined it: not rotated with the material.
    Mat3 strain = Mat3::Zero();
    double mu = 0.0;               // the hydrostat's volumetric strain rho/rho0 - 1 - opening_strain, last step
    double mu_max = 0.0;           // history maximum of mu (>= 0)
    double crushing_strain = 0.0;  // mu_p, plastic volumetric strain of the hydrostat
    double d_minus = 0.0;          // compressive damage (eq. 36)
    double d_plus = 0.0;           // tensile damage (SDEL, eq. 37)
    double tensile_strain_max = 0.0;  // kappa: history maximum of the equivalent tensile strain (over DIF)
    // AfcOptions::tensile_rate: the history maximum of e itself and the DIF held since it last grew.
    double tensile_strain_reached = 0.0;
    double tensile_dif = 1.0;
    double plastic_strain = 0.0;   // equivalent (deviatoric) plastic strain
    double plastic_work = 0.0;     // J per unit reference volume: deviatoric plastic work
    // OpenedVolume::Permanent: the volumetric strain opened past the tensile cutoff (<= 0, kept) and the
    // work of the cutoff pressure over it (J per unit reference volume, dissipated).
    double opening_strain = 0.0;
    double opening_work = 0.0;
    // SdelRegularization::CrackBand (cutoff coupling): the energy dissipated per unit reference volume in
    // the steps where a tensile mechanism acted (eq. 35's return on the open side, the cutoff, the
    // principal-stress limit): their stress work less the change of the free energy. It drives d+ past
    // the onset. 0 with the other options.
    double tensile_work = 0.0;
    double crushing_work = 0.0;    // J per unit reference volume: crushing of the hydrostat
    double deviatoric_return = 1.0;  // S / q_trial of the last step's radial return (1: elastic step)
    bool at_tensile_cutoff = false;  // the last step's pressure was held at the cutoff
  };

  // Throws std::invalid_argument for inconsistent constants (non-positive moduli, lengths, C1 <= C2,
  // C9 <= C7, a non-monotone crushing curve, eps_min <= 0, ...). afc_config.hpp turns file problems
  // into InputErrors before this point.
  explicit AfcMaterial(const AfcParams& params);

  // Precondition: step.spacing_m > 0 (the solver passes h_I) when the SDEL is on.
  void update(State& state, const MaterialStep& step) const;
  // Dilatational wave speed sqrt((K + 4G/3) / rho), K = rho dP/drho = (1 + mu) dP/dmu the current
  // tangent of the hydrostat (AfcOptions::wave_speed_from_unloading_modulus for the bound).
  double wave_speed(const State& state, double density_ratio) const;
  // A fully failed point (d+ = 1) that is open and hands the solver no stress (with the split: no
  // compressive principal stress left either): it resists nothing until it closes. Open: expanded past
  // its reference density (OpenedVolume::Recoverable), or with the permanent opening held at the zero
  // cutoff by its last update (the hydrostat read no compression).
  bool stress_free(const State& state, double density_ratio) const;
  double reference_density() const { return p_.density_kg_m3; }
  // For NSNI: the current tangent (1 + mu) dP/dmu of the hydrostat (the crushing slope while loading on
  // the curve, K_u below it), G, the last return, the cutoff and the split's factor 1 - d+.
  Moduli moduli(const State& state) const;
  void rotate(State& state, const Mat3& R) const;
  bool splits_stress() const { return p_.options.tensile_degradation == TensileDegradation::Split; }
  const Mat3& effective_stress(const State& state) const { return state.effective_stress; }
  // Free energy per unit current volume, 1/2 sigma : C_u^-1 : sigma_e (eq. 21: (1 - d+) Psi0+ + Psi0-
  // with the split), C_u the elastic unloading moduli (K_u(mu_max), G).
  double stored_energy(const State& state) const;
  DissipationParts dissipation(const State& state) const {
    return {state.plastic_work, state.crushing_work, state.opening_work};
  }

  // Per-particle output fields, one value each, in this order.
  static std::vector<std::string> output_fields() {
    return {"damage_tension", "damage_compression", "plastic_strain", "tensile_strain_max"};
  }
  void output_values(const State& state, double* out) const;

  const AfcParams& params() const { return p_; }
  const AfcHydrostat& hydrostat() const { return hydro_; }
  // The equivalent tensile strain of a strain tensor by the Mazars or MaxPrincipal measure.
  double equivalent_tensile_strain(const Mat3& strain) const;
  // The EffectiveTensile measure of a driver stress: the norm of the positive principal strains of
  // C^-1 : <sigma_bar>+ (C from K_e and G).
  double effective_tensile_strain(const Mat3& driver_stress) const;
  // The SDEL d+ at history strain kappa for spacing h (with the zero-anchoring option): the paper's
  // lambda = h / l_mac law (SdelRegularization::CrackBand evaluates it at h = l_ref).
  double sdel_damage(double kappa, double spacing_m) const;
  // SdelRegularization::CrackBand with the cutoff coupling: d+ of the reference curve at a tensile work per
  // volume already scaled by band_width(h) / l_ref (0 at and below 0, the onset's d+ just above, 1 past failure).
  double crack_band_damage(double scaled_tensile_work) const;
  // The onset of the reference curve: d+ of the reference at the peak of its uniaxial tension.
  double crack_band_onset() const { return band_.onset; }
  // The width of the band a point of spacing h stands for (AfcOptions::crack_band_width_spacings).
  double band_width(double spacing_m) const { return p_.options.crack_band_width_spacings * spacing_m; }
  // AfcOptions::crack_band_strength_reduction: the factor on Tmax of a band `band_width_m` wide and the d+ at
  // its peak in quasi-static uniaxial stress (1 and the reference's onset for a band the law holds).
  struct BandStrength {
    double tmax_scale = 1.0;
    double peak_damage = 0.0;
  };
  BandStrength band_strength(double band_width_m) const;
  // The widest band, in reference sizes l_ref, the cutoff coupling's crack band holds to at a point (its
  // energy within 0.5 %: +0.01 % at 1.2 l_ref, +1.3 % at 1.4 l_ref).
  static constexpr double kHoldingWidth = 1.2;
  // The widest band the strength reduction holds, in w_lim (its table's range; past it the factor stays
  // at the table's last and the band snaps back again: the crack_band_too_wide warning says so).
  static constexpr double kStrengthRange = 20.0;

 private:
  // The principal-stress limit's return of the deviator s at pressure P (AfcOptions::principal_stress_limit).
  void limit_principal_stress(State& state, Mat3& s, double P, double dif, double density_ratio) const;

  // The reference curve of SdelRegularization::CrackBand (construction).
  void build_crack_band_curve();
  // AfcOptions::crack_band_strength_reduction (construction): the table of band_strength.
  void build_band_strength_table();
  // The strain and d+ at the peak of quasi-static uniaxial stress with Tmax scaled by s (the crack band's
  // pre-onset d+ = min(SDEL(kappa, l_ref), onset); no rate, d- = 0): E eps = a / (1 + a / (3 s Tmax (1 - d+))).
  // The Lode factor and the principal-stress limit are not in it: with them the factor is approximate (the
  // band's energy still holds, within 2 % measured, but d+ may jump by 0.05 at the first yielding step).
  std::pair<double, double> uniaxial_peak(double tmax_scale) const;

  AfcParams p_;
  AfcHydrostat hydro_;
  double principal_limit_ = 0.0;  // T_R of the principal-stress limit (Pa)
  // The reference curve of SdelRegularization::CrackBand (cutoff coupling): the tensile work per volume of
  // the reference point in uniaxial tension at kBandPoints values of d+ evenly spaced from the onset to 1.
  // A fixed array: copying the law (the solver's saved state) allocates nothing.
  bool track_tensile_work_ = false;  // accumulate State::tensile_work (the crack band and its reference)
  bool reduce_band_strength_ = false;  // AfcOptions::crack_band_strength_reduction, on a crack band it acts on
  static constexpr int kBandPoints = 512;
  struct CrackBandCurve {
    double onset = 1.0;
    std::array<double, kBandPoints> work{};
  } band_;
  // The table of band_strength: at kStrengthPoints widths log-spaced from w_lim = kHoldingWidth l_ref to
  // kStrengthRange w_lim, the factor on Tmax that puts the elastic energy at the band's peak at the holding
  // band's times w_lim / w (so the peak never holds more than the band's share of G_ref), and the peak's d+.
  static constexpr int kStrengthPoints = 64;
  struct BandStrengthTable {
    std::array<double, kStrengthPoints> scale{}, peak_damage{};
  } strength_;
};

}  // namespace uhpc::macro
