#include "panel_damage.hpp"

#include <algorithm>
#include <cmath>

namespace uhpc::macro {

namespace {

void add(Debris& d, double m, double vz) {
  d.velocity_m_s = (d.velocity_m_s * d.mass_kg + vz * m) / (d.mass_kg + m);
  d.mass_kg += m;
  ++d.particles;
}

}  // namespace

PanelDamage panel_damage(const Particles& p, const std::vector<double>& reference, const std::vector<double>& damage,
                         double thickness_m, double impact_x_m, double sphere_vz_m_s) {
  PanelDamage out;
  const bool measured = damage.size() == p.n;
  double r_front = measured ? 0.0 : -0.5, r_rear = measured ? 0.0 : -0.5;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (measured && damage[i] >= kFailedDamage) {
      const double z0 = reference[3 * i + 2], h = p.spacing[i];
      const double r = std::hypot(reference[3 * i] - impact_x_m, reference[3 * i + 1]);
      if (z0 < h) r_front = std::max(r_front, r);
      if (z0 > thickness_m - h) r_rear = std::max(r_rear, r);
    }
    const double z = p.x[3 * i + 2], vz = p.v[3 * i + 2], m = p.mass[i];
    if (z < 0.0 && vz < 0.0) add(out.front_ejecta, m, vz);
    if (z > thickness_m && vz > 0.0) {
      add(out.rear_ejecta, m, vz);
      if (sphere_vz_m_s > 0.0 && vz >= kPlugSpeedShare * sphere_vz_m_s) add(out.plug, m, vz);
    }
  }
  out.front_crater_diameter_m = 2.0 * r_front;
  out.rear_scab_diameter_m = 2.0 * r_rear;
  return out;
}

}  // namespace uhpc::macro
