#pragma once
// Structured particle generators for the 3D bodies: a box, a cylinder (a bar along z) and the target
// disc with radially graded spacing. The volumes are exact shares of the body (they sum to its
// volume to round-off), so mass and momentum start right whatever the grading.
#include "bodies/particle_body.hpp"

namespace uhpc::macro {

// Box [0, Lx] x [0, Ly] x [0, Lz] on a cell-centred lattice of about `spacing` (each edge divided
// into round(L / spacing) equal cells).
ParticleBody box_body(double lx, double ly, double lz, double spacing);

// Disc (or bar) of radius R about the z axis, z in [z0, z0 + length], in concentric rings.
// The in-plane spacing is h_axis up to `core_radius` and grows linearly to h_rim at R; each ring is
// divided through the length into round(length / h) layers of its own h. Ring widths follow the local
// spacing and are rescaled so the last ring ends exactly at R; each ring holds round(2 pi r / h)
// particles, and alternate rings are rotated by half a step so no radial lines of particles form.
struct DiscSpec {
  double radius_m = 0;
  double thickness_m = 0;
  double z0_m = 0;          // lowest face
  double h_axis_m = 0;      // spacing at the axis
  double h_rim_m = 0;       // spacing at the rim
  double core_radius_m = 0; // uniform h_axis inside this radius (0: grade from the axis)
};
ParticleBody disc_body(const DiscSpec& spec);

// The nominal in-plane spacing of a DiscSpec at radius r.
double disc_spacing_at(const DiscSpec& spec, double r);

// Particle counts known before a body is built, so that a run can be refused before it allocates:
// exact for the box; for the disc the integral of the lattice density 2 pi r T / h(r)^3 over the radius
// (within a few per cent of disc_body's count, which rounds every ring and layer).
double box_particle_count(double lx, double ly, double lz, double spacing);
double disc_particle_estimate(const DiscSpec& spec);

}  // namespace uhpc::macro
