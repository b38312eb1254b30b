#pragma once
// Constants and options of the AFC concrete model with SDEL tensile damage (docs/physics.md section 4).
// AfcParams holds the paper's Table 6 in SI plus the SDEL handoff; AfcOptions holds every gap the paper
// leaves open ([choice] in docs/physics.md) as a named field with its default. macro/README.md lists them.
#include "uhpc/sdel.hpp"

namespace uhpc::macro {

// The equivalent tensile strain that drives the SDEL (the handoff's "strain_measure").
enum class TensileStrainMeasure {
  // sqrt(sum of squared positive principal strains) of eps+ = C^-1 : <sigma_bar>+, the elastic strain
  // produced by the positive principal effective stresses (default, docs/physics.md section 3): the
  // conjugate of the tensile free energy of eqs. 21-23. sigma_bar is AfcMaterial::State::driver_stress,
  // the stress of the material without tensile limits; C the elastic compliance (K_e, G).
  EffectiveTensile,
  Mazars,        // sqrt(sum of squared positive principal strains) of the summed total strain (option)
  MaxPrincipal,  // largest principal strain of the summed total strain, 0 when negative (option)
};

// How d+ acts on the stress (AfcOptions::tensile_degradation).
enum class TensileDegradation {
  // [default] The paper's AFC coupling (docs/physics.md section 4.5: "the two damage variables describe
  // the degradation of the tensile, d+, and shear, d-, failure surface"): d+ lowers the tensile cutoff to
  // Tmax (1 - d+) and T in eq. 35; the stress tensor itself is not degraded.
  Cutoff,
  // [option] eq. 21's split applied to the macro stress: the AFC stress with its undamaged tensile
  // limits (cutoff -Tmax, eq. 35 with T = Tmax) is the effective stress sigma_e kept in the state; the
  // solver gets sigma = <sigma_e>- + (1 - d+) <sigma_e>+ (principal parts). In uniaxial tension this is
  // the microcells' (1 - d) E e up to AFC's own undamaged strength. Eq. 21 is the energy bridging that
  // defines d+ from the microcells, not the paper's macro coupling.
  Split,
};

// [choice] The third-invariant (Lode) dependence of the strength (AfcOptions::lode). The paper calls AFC
// a three-invariant model but prints only the compressive meridian (eqs. 33, 35).
enum class LodeDependence {
  Off,  // [default] S(P) on every meridian (Drucker-Prager-like): triaxial extension as strong as compression
  // S(P) r(theta, psi): Willam-Warnke's elliptic interpolation (Willam and Warnke 1975) between the
  // compressive meridian (r = 1: eqs. 33/35 as printed, fitted to triaxial compression) and the
  // extension meridian (r = psi). psi(P) = 3 / (3 + dS/dP): the ratio of Mohr-Coulomb's meridians,
  // (3 - sin phi) / (3 + sin phi), for the friction of the current compressive meridian's local slope
  // (e.g. Chen and Han, Plasticity for Structural Engineers, 1988, section 5.3), clipped to [0.5, 1]
  // (convexity of the ellipse); for P < 0 psi takes its value at P = 0.
  WillamWarnke,
};

// [choice] A principal-stress (Rankine) limit sigma_1 <= T_R (1 - d+) (AfcOptions::principal_stress_limit),
// applied after the return onto S as a second plastic return of the deviator at fixed pressure (the
// closest admissible deviator, no dilatancy), never by scaling a stored stress.
enum class PrincipalStressLimit {
  Off,                        // [default] the paper's surfaces alone
  UniaxialTensileStrength,    // T_R = f't, eq. 35's uniaxial tensile strength of the intact material (15.9 MPa)
  Tmax,                       // T_R = Tmax (the form first asked for; below f't, so it lowers f't to Tmax)
};

// [choice] Rate dependence of tensile failure (AfcOptions::tensile_rate). AFC's own rate factor
// 1 + C3 ln(edot / edot0) acts on the deviatoric strength only (1.05-1.2 at impact rates); UHPC's
// measured dynamic increase of tensile strength is 2-4 at about 1e2 1/s.
enum class TensileRate {
  Off,  // [default] the paper's model: Tmax and the SDEL do not depend on the rate
  // The tensile DIF of the fib Model Code 2010 (section 5.1.11.2, eqs. 5.1-106 and 5.1-107):
  //   DIF = (edot / edot0)^0.018 for edot <= 10 1/s, 0.0062 (edot / edot0)^(1/3) above, edot0 = 1e-6 1/s,
  // floored at 1; edot the step's largest principal strain rate (0 when nothing stretches). It raises
  // the tensile cutoff to DIF Tmax (1 - d+) (and T in eq. 35) and delays d+: kappa grows by each new
  // increment of the tensile strain's history maximum over the DIF of the step that made it, and the
  // DIF is held while that maximum does not grow (a step with no stretch neither jumps kappa to e nor
  // drops the cutoff). At a constant rate kappa = e / DIF: the damage curve stretched by DIF.
  FibModelCode2010,
};

// [choice] How a point that opened past the tensile cutoff takes pressure again (AfcOptions::opened_volume).
enum class OpenedVolume {
  // [default] The volumetric strain opened past the cutoff is kept as a permanent (plastic) opening
  // mu_o <= 0 and the hydrostat reads mu - mu_o: re-compression loads from the opened state at once along
  // the unloading line (as HJC's incremental pressure clipped at the tensile limit forgets opened
  // volume). Why: confined rubble carries pressure from its current packing
  // (docs/studies/2026-12-06-slow-sphere.md).
  Permanent,
  // [option; the paper-model case's] P from the density ratio to the intact density: a point that opened
  // by mu < 0 carries no pressure until it is pushed back to its closed density (a closure slack equal to
  // the opened volume); a fully failed open point is stress-free.
  Recoverable,
};

// [choice] How the SDEL is regularized with the particle spacing h_I (AfcOptions::sdel_regularization).
// The energy a crack band one particle wide dissipates per unit crack area is G = h W(h), W the work per
// volume of a point taken to full damage (docs/studies/2026-12-06-crack-band.md).
enum class SdelRegularization {
  // [default] The paper's law: d+ = SDEL(lambda_I, kappa), lambda_I = h_I / l_mac (eqs. 25, 37). lambda
  // steepens the softening beyond e_i, but the energy stored up to e_i and the peak move with h too, so G
  // is not independent of h (uniaxial tension, 1.5 to 6.0 mm: G 8.5-10.1 J/m^2 for the SDEL alone, 9.9-13.2
  // with the cutoff coupling).
  Lambda,
  // A crack band (Bazant and Oh 1983) on the SDEL of a fixed reference size l_ref
  // (AfcOptions::crack_band_reference_size_m): a point of any spacing h dissipates l_ref / h times what the
  // reference point does, so G = h W is the reference's l_ref W_ref at every h.
  //  - cutoff coupling (d+ acts on the limits; what dissipates is the return onto them and the release of
  //    the energy they cut): up to the reference's onset of tensile yielding (its peak in uniaxial
  //    tension) d+ = SDEL(l_ref / l_mac, kappa), capped at the onset's d+; past it d+ = D(W_t h / l_ref),
  //    W_t the energy the point has dissipated in steps where a tensile mechanism acted
  //    (State::tensile_work) and D the reference's d+ against that energy in quasi-static uniaxial
  //    tension (computed once, at construction). The point fails when W_t = W_ref l_ref / h, whatever its
  //    stress path (a laterally held point as well as a free one). W_t is the steps before's (explicit).
  //  - split ((1 - d+) on the tensile stress): the reference band at the same crack opening, the root of
  //    u = e_el + (kappa - e_el) h / l_ref with e_el = (1 - d_ref(u)) min(u, e_e) the elastic part, and
  //    1 - d+ = (1 - d_ref(u)) min(u, e_e) / e_e (e_e the effective stress's measure): exact in uniaxial
  //    tension.
  // Holds for h up to about 1.4 l_ref (cutoff) and l_ref (split); above, a point's elastic energy at its
  // peak exceeds its share and it snaps back, dissipating more (cutoff) or less (split).
  CrackBand,
};

// Where the tensile damage d+ comes from.
enum class TensileDamage {
  Sdel,  // the SDEL with lambda = h_I / l_mac (default: the paper's model)
  Off,   // d+ stays 0: Table 6's strength surfaces alone (verification of eq. 35, comparisons)
};

struct AfcOptions {
  // [choice] The rate factor 1 + C3 ln(edot / edot0) is not allowed below this floor. 1 (default):
  // rates below the reference rate give the quasi-static strength. 0: the raw law, cut at zero.
  double rate_factor_floor = 1.0;
  // [choice] C5's role is not given in the paper. false (default): C5 is kept in AfcParams and unused.
  // true: C5 caps the rate-free strength of eq. 33/35 before the rate factor, S = F min(S_static, C5).
  bool cap_strength_with_c5 = false;
  // [choice] eq. 36's floor of the pressure term: d- += d eps_p / max(P D1, eps_min) + ...
  double damage_eps_min = 0.01;
  // [choice] how d+ acts on the stress: the tensile cutoff and eq. 35 (default, the paper's) or eq. 21's split.
  TensileDegradation tensile_degradation = TensileDegradation::Cutoff;
  // [choice] third-invariant dependence of the strength (off by default).
  LodeDependence lode = LodeDependence::Off;
  // [choice] principal-stress limit of damaged material (off by default; needs the cutoff coupling).
  PrincipalStressLimit principal_stress_limit = PrincipalStressLimit::Off;
  // [choice] how opened material takes pressure again.
  OpenedVolume opened_volume = OpenedVolume::Permanent;
  // [choice] rate dependence of tensile failure (off by default).
  TensileRate tensile_rate = TensileRate::Off;
  // [choice] the SDEL as printed (false, default: d+(0) = 1/(1 + nu exp(lambda chi e_i)) > 0, about
  // 2e-5 at 3 mm) or shifted to start at exactly 0 (true, uhpc::sdel_damage_zero_anchored).
  bool sdel_zero_anchored = false;
  // [choice] the paper's lambda scaling of the SDEL with h_I (default) or a crack band on the SDEL of the
  // reference size below (SdelRegularization).
  SdelRegularization sdel_regularization = SdelRegularization::Lambda;
  // [choice] l_ref of SdelRegularization::CrackBand: 6.5 mm, the largest microcell size the SDEL was
  // calibrated at (no extrapolation in lambda, the most representative cell), so every spacing of the
  // shipped cases (1.5-4.5 mm; the coarse disc's 6-9 mm) is at or below the 1.4 l_ref the crack band holds
  // to with the cutoff coupling (with the split, up to l_ref). G = 13.6 J/m^2 with the paper's SDEL and the cutoff coupling, 10.5 J/m^2 for the SDEL alone.
  double crack_band_reference_size_m = 0.0065;
  // [choice] The width of the band a crack opens in, in particle spacings (SdelRegularization::CrackBand):
  // a point of spacing h stands for a band n_b h wide and dissipates l_ref / (n_b h) times the reference
  // point's energy per volume, so a crack n_b layers wide dissipates G_ref. 1 (default): the band is one
  // particle, as a crack band in finite elements is one element. In this solver a crack opens three layers
  // (the RK support of 2.5 h strains the layers beside an opening one: docs/studies/2026-12-06-crack-band.md),
  // which is what 3 stands for. The band's limit (above) then reads n_b h up to about 1.4 l_ref.
  double crack_band_width_spacings = 1.0;
  // [choice] Bazant and Oh's strength reduction for bands too wide to hold (SdelRegularization::CrackBand with
  // the cutoff coupling). false (default): the strength is kept, and a band w = n_b h wider than the law
  // holds to (w_lim = AfcMaterial::kHoldingWidth l_ref = 7.8 mm) snaps back at its peak (its elastic energy
  // there exceeds its share of G_ref) and dissipates more. true: such a point's Tmax is lowered so that its
  // elastic energy at the peak of quasi-static uniaxial stress (where E eps meets the limit at the d+ the
  // SDEL gives that strain) is the holding band's times w_lim / w, and its d+ curve starts at that peak's d+
  // (AfcMaterial::band_strength, tabulated at construction). What it dissipates is still the band's share:
  // G = w W = l_ref W_ref at a point, in uniaxial stress and laterally held (unit.AfcCrackBand).
  bool crack_band_strength_reduction = false;
  // Verification switch (not a modelling choice of the paper): TensileDamage::Off keeps d+ = 0.
  TensileDamage tensile_damage = TensileDamage::Sdel;
  // [choice] The wave speed (hence the stable step) uses the current tangent bulk modulus of the
  // hydrostat (false, default: K_e, the crushing slope, C8; the unloading modulus below mu_max). true:
  // always the unloading modulus, an upper bound of every slope the point can take in the next step
  // (an unloading wave from a crushing state travels at it; about 1.2x the crushing-onset speed).
  bool wave_speed_from_unloading_modulus = false;
};

struct AfcParams {
  double density_kg_m3 = 0;
  double shear_modulus_Pa = 0;  // G
  double C1_Pa = 0, C2_Pa = 0;  // failure surface constants
  double C3 = 0;                // rate sensitivity
  double C4 = 0;                // pressure slope of the failure surface
  double C5_Pa = 0;             // see AfcOptions::cap_strength_with_c5
  double C6_Pa = 0;             // pressure where crushing begins
  double C7 = 0;                // volumetric strain where crushing begins
  double C8_Pa = 0;             // locking modulus
  double C9 = 0;                // volumetric strain where locking begins
  double K1_Pa = 0, K2_Pa = 0, K3_Pa = 0;  // crushing polynomial in x = mu - C7
  double D1_1_Pa = 0;           // compressive damage constant (eq. 36)
  double An_1_Pa = 0;           // failure surface constant (eq. 33)
  double Tmax_Pa = 0;           // maximum tensile pressure
  double reference_strain_rate_1_s = 1e-4;  // edot0 (eq. 34)

  SdelConstants<double> sdel{};  // a, A, nu, chi (the micro-to-macro handoff)
  double l_mac_m = 0.4064;
  TensileStrainMeasure strain_measure = TensileStrainMeasure::EffectiveTensile;

  AfcOptions options{};
};

}  // namespace uhpc::macro
