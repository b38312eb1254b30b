#pragma once
// What a test engineer measures on the panel after a shot: the front crater and the rear scab, and the
// debris thrown out of either face, with the plug that leaves with the sphere (macro/README.md,
// result.json's `panel`). Read from the particles' reference positions (which face layer a particle
// belongs to, how far from the impact point it sat), their damage and their current state.
#include <vector>

#include "solver/particles.hpp"

namespace uhpc::macro {

// A particle counts as failed when its larger damage (d+ or d-) reaches this.
inline constexpr double kFailedDamage = 0.99;
// A particle past the exit face belongs to the plug when it moves along the normal at least this share
// of the sphere's own speed: it leaves with the sphere.
inline constexpr double kPlugSpeedShare = 0.5;

struct Debris {
  double mass_kg = 0.0;
  double velocity_m_s = 0.0;  // along the panel's normal (+z, the sphere's way): momentum / mass; 0 without mass
  int particles = 0;
};

struct PanelDamage {
  // 2 x the largest distance from the impact point (in the face's plane, in the reference configuration)
  // of a failed particle of the face's first layer (reference centre within its own spacing of the face);
  // 0 when none failed there. Negative when the law has no damage (not measured).
  double front_crater_diameter_m = -1.0;
  double rear_scab_diameter_m = -1.0;
  Debris front_ejecta;  // centre before the entry face (z < 0), moving back (v_z < 0)
  Debris rear_ejecta;   // centre past the exit face (z > thickness), moving on (v_z > 0)
  Debris plug;          // of the rear ejecta, those at kPlugSpeedShare of the sphere's v_z or faster
};

// `reference` the particles' reference positions (3n), `damage` their larger damage (n, empty: the law
// has none), the entry face at z = 0 and the exit face at z = thickness, the impact point at (impact_x, 0).
PanelDamage panel_damage(const Particles& p, const std::vector<double>& reference, const std::vector<double>& damage,
                         double thickness_m, double impact_x_m, double sphere_vz_m_s);

}  // namespace uhpc::macro
