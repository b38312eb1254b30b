#pragma once
// What a test engineer measures on the panel after a shot: the front crater and the rear scab, and the
// debris thrown out of either face, with the plug that leaves with the sphere (macro/README.md,
// result.json's `panel`). Read from the particles' reference positions (which face layer a particle
// belongs to, how far from the impact point it sat) and their current state. The crater is where the
// material has left its place, not where it is damaged: the tensile damage of the shipped model reaches
// 1 in a third of the face layer out to the rim (bending cracks), the material stays.
#include <vector>

#include "solver/particles.hpp"

namespace uhpc::macro {

// A particle has left its place when it has moved more than this share of its spacing.
inline constexpr double kMovedShare = 0.5;
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
  // of a particle of the face's first layer (reference centre within its own spacing of the face) that
  // has left its place; 0 when none has.
  double front_crater_diameter_m = 0.0;
  double rear_scab_diameter_m = 0.0;
  // How deep the material that left the panel through a face came from: the deepest far side (reference
  // centre + h/2 from the face) of a particle now out of the entry face (z < 0), and likewise for the
  // exit face (z > thickness); 0 when none has left. A crater and scab depth from where material left,
  // measured at the end of the run (ejecta still on their way out are not counted).
  double front_crater_depth_m = 0.0;
  double rear_scab_depth_m = 0.0;
  Debris front_ejecta;  // centre before the entry face (z < 0), moving back (v_z < 0)
  Debris rear_ejecta;   // centre past the exit face (z > thickness), moving on (v_z > 0)
  Debris plug;          // of the rear ejecta, those at kPlugSpeedShare of the sphere's v_z or faster
};

// `reference` the particles' reference positions (3n), the entry face at z = 0 and the exit face at
// z = thickness, the impact point at (impact_x, 0).
PanelDamage panel_damage(const Particles& p, const std::vector<double>& reference, double thickness_m,
                         double impact_x_m, double sphere_vz_m_s);

}  // namespace uhpc::macro
