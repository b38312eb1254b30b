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

PanelDamage panel_damage(const Particles& p, const std::vector<double>& reference, double thickness_m,
                         double impact_x_m, double sphere_vz_m_s) {
  PanelDamage out;
  double r_front = 0.0, r_rear = 0.0;
  bool front = false, rear = false;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double* x0 = &reference[3 * i];
    const double* x = &p.x[3 * i];
    const double h = p.spacing[i];
    if (std::hypot(x[0] - x0[0], x[1] - x0[1], x[2] - x0[2]) > kMovedShare * h) {
      const double r = std::hypot(x0[0] - impact_x_m, x0[1]);
      if (x0[2] < h) front = true, r_front = std::max(r_front, r);
      if (x0[2] > thickness_m - h) rear = true, r_rear = std::max(r_rear, r);
    }
    if (x[2] < 0.0) out.front_crater_depth_m = std::max(out.front_crater_depth_m, x0[2] + 0.5 * h);
    if (x[2] > thickness_m) out.rear_scab_depth_m = std::max(out.rear_scab_depth_m, thickness_m - (x0[2] - 0.5 * h));
    const double vz = p.v[3 * i + 2], m = p.mass[i];
    if (x[2] < 0.0 && vz < 0.0) add(out.front_ejecta, m, vz);
    if (x[2] > thickness_m && vz > 0.0) {
      add(out.rear_ejecta, m, vz);
      if (sphere_vz_m_s > 0.0 && vz >= kPlugSpeedShare * sphere_vz_m_s) add(out.plug, m, vz);
    }
  }
  out.front_crater_diameter_m = front ? 2.0 * r_front : 0.0;
  out.rear_scab_diameter_m = rear ? 2.0 * r_rear : 0.0;
  return out;
}

}  // namespace uhpc::macro
