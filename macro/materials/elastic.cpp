#include "materials/elastic.hpp"

#include <cmath>
#include <stdexcept>

namespace uhpc::macro {

ElasticMaterial::ElasticMaterial(const ElasticParams& params) : p_(params) {
  if (!(p_.density_kg_m3 > 0) || !(p_.bulk_modulus_Pa > 0) || !(p_.shear_modulus_Pa > 0))
    throw std::invalid_argument("ElasticMaterial: density, bulk and shear modulus must be > 0");
}

void ElasticMaterial::update(State& state, const MaterialStep& step) const {
  const Mat3& de = step.strain_increment;
  state.stress += p_.bulk_modulus_Pa * de.trace() * Mat3::Identity() + 2.0 * p_.shear_modulus_Pa * deviator(de);
}

double ElasticMaterial::wave_speed(const State&, double density_ratio) const {
  return std::sqrt((p_.bulk_modulus_Pa + 4.0 / 3.0 * p_.shear_modulus_Pa) / (p_.density_kg_m3 * density_ratio));
}

}  // namespace uhpc::macro
