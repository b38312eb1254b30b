#include "materials/j2_plasticity.hpp"

#include <cmath>
#include <stdexcept>

namespace uhpc::macro {

J2Material::J2Material(const J2Params& params) : p_(params) {
  if (!(p_.density_kg_m3 > 0) || !(p_.bulk_modulus_Pa > 0) || !(p_.shear_modulus_Pa > 0) ||
      !(p_.yield_stress_Pa > 0) || !(p_.hardening_modulus_Pa >= 0))
    throw std::invalid_argument(
        "J2Material: density, moduli and yield stress must be > 0, hardening modulus >= 0");
}

void J2Material::update(State& state, const MaterialStep& step) const {
  const double G = p_.shear_modulus_Pa, K = p_.bulk_modulus_Pa, H = p_.hardening_modulus_Pa;
  const Mat3& de = step.strain_increment;
  const double pressure = pressure_of(state.stress) - K * de.trace();
  const Mat3 s_trial = deviator(state.stress) + 2.0 * G * deviator(de);
  const double q_trial = std::sqrt(1.5 * s_trial.cwiseProduct(s_trial).sum());
  const double f = q_trial - yield_stress(state.plastic_strain);
  Mat3 s = s_trial;
  state.deviatoric_return = 1.0;
  if (f > 0.0) {
    // Radial return: with linear hardening the consistency condition is linear in d eps_p.
    const double dep = f / (3.0 * G + H);
    state.deviatoric_return = 1.0 - 3.0 * G * dep / q_trial;
    s *= state.deviatoric_return;
    const double ep0 = state.plastic_strain, ep1 = ep0 + dep;
    state.plastic_work += p_.yield_stress_Pa * dep + 0.5 * H * (ep1 * ep1 - ep0 * ep0);
    state.plastic_strain = ep1;
  }
  state.stress = s - pressure * Mat3::Identity();
}

double J2Material::wave_speed(const State&, double density_ratio) const {
  // The elastic speed bounds the plastic one: safe for the stable time step.
  return std::sqrt((p_.bulk_modulus_Pa + 4.0 / 3.0 * p_.shear_modulus_Pa) / (p_.density_kg_m3 * density_ratio));
}

}  // namespace uhpc::macro
