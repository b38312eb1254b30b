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
  // [choice, default] eq. 21's split: the AFC stress with its undamaged tensile limits (cutoff -Tmax,
  // eq. 35 with T = Tmax) is the effective stress sigma_e kept in the state; the solver gets
  // sigma = <sigma_e>- + (1 - d+) <sigma_e>+ (principal parts). In uniaxial tension this is the
  // microcells' (1 - d) E e up to AFC's own undamaged strength.
  Split,
  // The paper's AFC coupling as docs/physics.md section 4 states it: d+ lowers the tensile cutoff to
  // Tmax (1 - d+) and T in eq. 35; the stress tensor itself is not degraded.
  Cutoff,
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
  // [choice] how d+ acts on the stress: eq. 21's split (default) or the tensile cutoff and eq. 35.
  TensileDegradation tensile_degradation = TensileDegradation::Split;
  // [choice] the SDEL as printed (false, default: d+(0) = 1/(1 + nu exp(lambda chi e_i)) > 0, about
  // 2e-5 at 3 mm) or shifted to start at exactly 0 (true, uhpc::sdel_damage_zero_anchored).
  bool sdel_zero_anchored = false;
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
