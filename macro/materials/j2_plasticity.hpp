#pragma once
// J2 (von Mises) plasticity with linear isotropic hardening, for verification on classical metal
// impact problems: elastic predictor, radial return of the deviatoric trial stress at fixed pressure,
// sigma_y(eps_p) = yield_stress + hardening_modulus * eps_p.
#include <string>
#include <vector>

#include "materials/material_step.hpp"

namespace uhpc::macro {

struct J2Params {
  double density_kg_m3 = 0;
  double bulk_modulus_Pa = 0;
  double shear_modulus_Pa = 0;
  double yield_stress_Pa = 0;
  double hardening_modulus_Pa = 0;  // d sigma_y / d eps_p (>= 0)
};

class J2Material {
 public:
  struct State {
    Mat3 stress = Mat3::Zero();
    double plastic_strain = 0.0;  // equivalent plastic strain
    double plastic_work = 0.0;    // integral of sigma_y d eps_p, J per unit volume
    double deviatoric_return = 1.0;  // sigma_y / q_trial of the last step (1: elastic step)
  };

  // Throws std::invalid_argument for non-positive density, moduli or yield stress, or negative H.
  explicit J2Material(const J2Params& params);

  void update(State& state, const MaterialStep& step) const;
  double wave_speed(const State& state, double density_ratio) const;
  bool stress_free(const State&, double) const { return false; }  // never: the metal does not fail
  double reference_density() const { return p_.density_kg_m3; }
  // The elastic moduli and the last return (linearised radial return with linear hardening: the
  // component along the deviator follows the yield stress by H / (3G + H)).
  Moduli moduli(const State& state) const {
    return {p_.bulk_modulus_Pa, p_.shear_modulus_Pa, state.deviatoric_return,
            p_.hardening_modulus_Pa / (3.0 * p_.shear_modulus_Pa + p_.hardening_modulus_Pa), false};
  }
  void rotate(State& state, const Mat3& R) const { state.stress = R * state.stress * R.transpose(); }
  bool splits_stress() const { return false; }
  const Mat3& effective_stress(const State& state) const { return state.stress; }
  double stored_energy(const State& state) const {
    return half_compliance_product(state.stress, state.stress, p_.bulk_modulus_Pa, p_.shear_modulus_Pa);
  }
  // The plastic work (the hardening energy included, as is usual for isotropic hardening).
  DissipationParts dissipation(const State& state) const { return {state.plastic_work, 0.0}; }
  double yield_stress(double plastic_strain) const {
    return p_.yield_stress_Pa + p_.hardening_modulus_Pa * plastic_strain;
  }
  const J2Params& params() const { return p_; }
  // Per-particle output fields beyond the solver's: output_values writes one value per name, in order.
  static std::vector<std::string> output_fields() { return {"plastic_strain"}; }
  void output_values(const State& state, double* out) const { out[0] = state.plastic_strain; }

 private:
  J2Params p_;
};

}  // namespace uhpc::macro
