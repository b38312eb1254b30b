#pragma once
// What a test engineer measures on the panel after a shot: the front crater and the rear scab, and the
// debris thrown out of either face, with the plug that leaves with the sphere (macro/README.md,
// result.json's `panel`). Read from the particles' reference positions (which face layer a particle
// belongs to, how far from the impact point it sat) and their current state. The crater is where the
// material has left its place, not where it is damaged: the tensile damage of the shipped model reaches
// 1 in a third of the face layer out to the rim (bending cracks), the material stays.
#include <optional>
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
  // 2 x the largest distance from where the shot line crosses the face (in the face's plane, in the
  // reference configuration) of a particle of the face's first layer (reference centre within its own
  // spacing of the face) that has left its place; 0 when none has.
  double front_crater_diameter_m = 0.0;
  double rear_scab_diameter_m = 0.0;
  // How deep the material that left the panel through a face came from: the deepest far side (reference
  // centre + h/2 from the face) of a particle now out of the entry face (z < 0), and likewise for the
  // exit face (z > thickness); 0 when none has left. A crater and scab depth from where material left,
  // measured at the end of the run (ejecta still on their way out are not counted).
  double front_crater_depth_m = 0.0;
  double rear_scab_depth_m = 0.0;
  // The narrowest clear opening through the panel: in slices parallel to the faces (a quarter of the
  // smallest spacing thick) across the thickness, the distance from the shot line to the nearest
  // particle's edge (current centre less h/2) of the material in the slice, doubled, and its least over
  // the slices. The material in a slice is every particle whose current extent (centre +- h/2) reaches
  // into it, the plug excepted (it leaves with the sphere); loose rubble left in the hole closes it, as
  // it would a gauge pushed through. 0 when material still lies on the shot line at some depth.
  double hole_diameter_m = 0.0;
  // The rear face's displacement along the normal (+: the sphere's way) at the shot line: the mass-mean
  // z-displacement of the exit face layer's particles within the sphere's radius of where the shot line
  // crosses the exit face (reference configuration), a scab that left there included. Not defined (empty)
  // when the panel is perforated: the face there left with the sphere.
  std::optional<double> rear_face_deflection_m;
  Debris front_ejecta;  // centre before the entry face (z < 0), moving back (v_z < 0)
  Debris rear_ejecta;   // centre past the exit face (z > thickness), moving on (v_z > 0)
  Debris plug;          // of the rear ejecta, those at kPlugSpeedShare of the sphere's v_z or faster
};

// The shot as the panel sees it: the entry face at z = 0 and the exit face at z = thickness_m, the shot
// line through the impact point (impact_x_m, 0, 0) drifting by lean_dx_dz along x per unit depth (the
// tangent of the obliquity; 0 for a normal impact), and the sphere at the end of the run.
struct ShotOnPanel {
  double thickness_m = 0.0;
  double impact_x_m = 0.0;
  double lean_dx_dz = 0.0;
  double sphere_radius_m = 0.0;
  double sphere_vz_m_s = 0.0;
  bool perforated = false;
};

// `reference` the particles' reference positions (3n).
PanelDamage panel_damage(const Particles& p, const std::vector<double>& reference, const ShotOnPanel& shot);

}  // namespace uhpc::macro
