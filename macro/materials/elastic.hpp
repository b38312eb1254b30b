#pragma once
// Linear (hypo)elastic material: sigma += K tr(de) I + 2 G dev(de) in the co-rotated frame.
#include <string>
#include <vector>

#include "materials/material_step.hpp"

namespace uhpc::macro {

struct ElasticParams {
  double density_kg_m3 = 0;
  double bulk_modulus_Pa = 0;
  double shear_modulus_Pa = 0;
};

class ElasticMaterial {
 public:
  struct State {
    Mat3 stress = Mat3::Zero();
  };

  // Throws std::invalid_argument unless density, K and G are > 0.
  explicit ElasticMaterial(const ElasticParams& params);

  void update(State& state, const MaterialStep& step) const;
  // Dilatational wave speed sqrt((K + 4G/3) / rho) at the current density.
  double wave_speed(const State& state, double density_ratio) const;
  // Whether the point carries no stress and resists no deformation at this density (never, elastic).
  bool stress_free(const State&, double) const { return false; }
  double reference_density() const { return p_.density_kg_m3; }
  Moduli moduli(const State&) const { return {p_.bulk_modulus_Pa, p_.shear_modulus_Pa}; }
  // The objective tensors of the state, rotated by the solver around each update: the stress.
  void rotate(State& state, const Mat3& R) const { state.stress = R * state.stress * R.transpose(); }
  // Whether the stress handed to the solver is a split of an effective stress (eq. 21): no.
  bool splits_stress() const { return false; }
  // The stress the NSNI gradient is returned with (the law has no split: the stress itself).
  const Mat3& effective_stress(const State& state) const { return state.stress; }
  // Elastic energy held per unit current volume, 1/2 sigma : C^-1 : sigma.
  double stored_energy(const State& state) const {
    return half_compliance_product(state.stress, state.stress, p_.bulk_modulus_Pa, p_.shear_modulus_Pa);
  }
  // Energy dissipated per unit reference volume so far (none for an elastic law).
  DissipationParts dissipation(const State&) const { return {}; }
  const ElasticParams& params() const { return p_; }
  // Per-particle output fields beyond the solver's (stress, pressure, ...): none for this law.
  static std::vector<std::string> output_fields() { return {}; }
  void output_values(const State&, double*) const {}

 private:
  ElasticParams p_;
};

}  // namespace uhpc::macro
