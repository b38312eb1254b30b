#include "panel_damage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace uhpc::macro {

namespace {

void add(Debris& d, double m, double vz) {
  d.velocity_m_s = (d.velocity_m_s * d.mass_kg + vz * m) / (d.mass_kg + m);
  d.mass_kg += m;
  ++d.particles;
}

bool in_plug(double vz, double sphere_vz) { return sphere_vz > 0.0 && vz >= kPlugSpeedShare * sphere_vz; }

// The clear opening along the shot line (PanelDamage::hole_diameter_m).
double hole_diameter(const Particles& p, const ShotOnPanel& shot) {
  const double h_min = *std::min_element(p.spacing.begin(), p.spacing.end());
  const double t = shot.thickness_m;
  const auto slices = static_cast<std::size_t>(std::ceil(t / (0.25 * h_min)));
  const double dz = t / static_cast<double>(slices);
  constexpr double kOpen = std::numeric_limits<double>::infinity();
  std::vector<double> clear(slices, kOpen);
  for (std::size_t i = 0; i < p.n; ++i) {
    const double* x = &p.x[3 * i];
    const double half = 0.5 * p.spacing[i];
    if (x[2] + half < 0.0 || x[2] - half > t || in_plug(p.v[3 * i + 2], shot.sphere_vz_m_s)) continue;
    const double r = std::max(0.0, std::hypot(x[0] - (shot.impact_x_m + shot.lean_dx_dz * x[2]), x[1]) - half);
    const auto first = static_cast<std::size_t>(std::max(0.0, std::floor((x[2] - half) / dz)));
    const auto last = std::min(slices - 1, static_cast<std::size_t>(std::max(0.0, std::floor((x[2] + half) / dz))));
    for (std::size_t k = first; k <= last; ++k) clear[k] = std::min(clear[k], r);
  }
  // A slice no particle reaches (the panel gone there altogether) does not narrow the hole.
  const double narrowest = *std::min_element(clear.begin(), clear.end());
  return narrowest == kOpen ? 0.0 : 2.0 * narrowest;
}

// The rear face's displacement at the shot line (PanelDamage::rear_face_deflection_m).
std::optional<double> rear_face_deflection(const Particles& p, const std::vector<double>& reference,
                                           const ShotOnPanel& shot, double exit_x) {
  if (shot.perforated) return std::nullopt;
  double mass = 0.0, mass_uz = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double* x0 = &reference[3 * i];
    if (x0[2] <= shot.thickness_m - p.spacing[i]) continue;  // not in the exit face layer
    if (std::hypot(x0[0] - exit_x, x0[1]) > shot.sphere_radius_m) continue;
    mass += p.mass[i];
    mass_uz += p.mass[i] * (p.x[3 * i + 2] - x0[2]);
  }
  if (mass == 0.0) return std::nullopt;
  return mass_uz / mass;
}

}  // namespace

PanelDamage panel_damage(const Particles& p, const std::vector<double>& reference, const ShotOnPanel& shot) {
  PanelDamage out;
  const double thickness_m = shot.thickness_m;
  const double exit_x = shot.impact_x_m + shot.lean_dx_dz * thickness_m;  // where the shot line leaves
  double r_front = 0.0, r_rear = 0.0;
  bool front = false, rear = false;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double* x0 = &reference[3 * i];
    const double* x = &p.x[3 * i];
    const double h = p.spacing[i];
    if (std::hypot(x[0] - x0[0], x[1] - x0[1], x[2] - x0[2]) > kMovedShare * h) {
      if (x0[2] < h) front = true, r_front = std::max(r_front, std::hypot(x0[0] - shot.impact_x_m, x0[1]));
      if (x0[2] > thickness_m - h) rear = true, r_rear = std::max(r_rear, std::hypot(x0[0] - exit_x, x0[1]));
    }
    if (x[2] < 0.0) out.front_crater_depth_m = std::max(out.front_crater_depth_m, x0[2] + 0.5 * h);
    if (x[2] > thickness_m) out.rear_scab_depth_m = std::max(out.rear_scab_depth_m, thickness_m - (x0[2] - 0.5 * h));
    const double vz = p.v[3 * i + 2], m = p.mass[i];
    if (x[2] < 0.0 && vz < 0.0) add(out.front_ejecta, m, vz);
    if (x[2] > thickness_m && vz > 0.0) {
      add(out.rear_ejecta, m, vz);
      if (in_plug(vz, shot.sphere_vz_m_s)) add(out.plug, m, vz);
    }
  }
  out.front_crater_diameter_m = front ? 2.0 * r_front : 0.0;
  out.rear_scab_diameter_m = rear ? 2.0 * r_rear : 0.0;
  if (p.n > 0) out.hole_diameter_m = hole_diameter(p, shot);
  out.rear_face_deflection_m = rear_face_deflection(p, reference, shot, exit_x);
  return out;
}

}  // namespace uhpc::macro
