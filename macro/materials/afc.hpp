#pragma once
// The AFC concrete model with SDEL tensile damage (PHYSICS.md section 4; equations as implemented and
// every option in macro/README.md, "AFC concrete model"). One step at a particle, in this order:
//   1. strain history: eps += d eps (the co-rotated increments summed, see State::strain);
//      e = equivalent tensile strain of eps (Mazars by default), kappa = max(kappa, e);
//      d+ = max(d+, SDEL(lambda, kappa)), lambda = h_I / l_mac (h_I = MaterialStep::spacing_m);
//   2. pressure from the hydrostat (afc_hydrostat.hpp) at mu = rho/rho0 - 1 with the cutoff
//      Tmax (1 - d+); mu_max and the crushing strain mu_p follow;
//   3. deviator: elastic trial s + 2G dev(d eps), radial return at fixed pressure (no dilatancy) onto
//      S(P, d-, d+, F) (afc_strength.hpp), F from the effective deviatoric rate of this step;
//      d eps_p = (q_trial - S) / (3G);
//   4. d- += d eps_p / max(P D1, eps_min) + d mu_p / (1.5 C9) while P > 0 (eq. 36), clipped to 1.
// d- enters the strength with its value at the start of the step (explicit), d+ with the new value.
#include <string>
#include <vector>

#include "materials/afc_hydrostat.hpp"
#include "materials/afc_params.hpp"
#include "materials/material_step.hpp"

namespace uhpc::macro {

class AfcMaterial {
 public:
  struct State {
    Mat3 stress = Mat3::Zero();
    // Sum of the strain increments D dt the solver hands the law (each in that step's co-rotated
    // frame). A hypoelastic code has no total strain; this sum is its small-strain stand-in and drives
    // the SDEL. The solver rotates only `stress`, so this sum is not rotated with the material: exact
    // for small rotations, which holds for concrete until it has cracked (d+ is then already
    // irreversible). See macro/README.md.
    Mat3 strain = Mat3::Zero();
    double mu = 0.0;               // volumetric strain rho/rho0 - 1 at the end of the last step
    double mu_max = 0.0;           // history maximum of mu (>= 0)
    double crushing_strain = 0.0;  // mu_p, plastic volumetric strain of the hydrostat
    double d_minus = 0.0;          // compressive damage (eq. 36)
    double d_plus = 0.0;           // tensile damage (SDEL, eq. 37)
    double tensile_strain_max = 0.0;  // kappa: history maximum of the equivalent tensile strain
    double plastic_strain = 0.0;   // equivalent (deviatoric) plastic strain
    double dissipated = 0.0;       // J per unit reference volume: deviatoric plastic work + crushing
    double tension_factor = 1.0;   // (1 - d+) applied to `stress` by degrade_tensile_stress, else 1
    double deviatoric_return = 1.0;  // S / q_trial of the last step's radial return (1: elastic step)
    bool at_tensile_cutoff = false;  // the last step's pressure was held at -Tmax (1 - d+)
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
  // A fully failed point (d+ = 1) that is open (expanded past its reference density): P = 0 and S = 0
  // on the tension side, so it carries no stress and resists nothing until it closes back to rho0.
  bool stress_free(const State& state, double density_ratio) const {
    return state.d_plus >= 1.0 && density_ratio < 1.0;
  }
  double reference_density() const { return p_.density_kg_m3; }
  // An upper bound of the tangent: (1 + mu) max(K_u, dP/dmu) and G (keeps the NSNI term stabilising).
  Moduli moduli(const State& state) const;
  double dissipated_energy(const State& state) const { return state.dissipated; }

  // Per-particle output fields, one value each, in this order.
  static std::vector<std::string> output_fields() {
    return {"damage_tension", "damage_compression", "plastic_strain"};  // pressure: the solver writes it
  }
  void output_values(const State& state, double* out) const;

  const AfcParams& params() const { return p_; }
  const AfcHydrostat& hydrostat() const { return hydro_; }
  // The equivalent tensile strain of a strain tensor by the law's measure.
  double equivalent_tensile_strain(const Mat3& strain) const;
  // The SDEL d+ at history strain kappa for spacing h (with the zero-anchoring option).
  double sdel_damage(double kappa, double spacing_m) const;

 private:
  AfcParams p_;
  AfcHydrostat hydro_;
};

}  // namespace uhpc::macro
