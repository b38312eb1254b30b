#pragma once
// The projectile: a free rigid sphere (mass, radius, position, velocity) in penalty contact with the
// particles, frictionless by default (PHYSICS.md section 5), Coulomb friction as an option.
//
// Contact model (penalty; the normal force first, friction below). Each particle I carries a contact radius r_I =
// contact_radius_factor * h_I (default h_I / 2: the particle's half spacing, so the body's surface and
// not its particle centres meets the sphere, as for the planar walls). With d = |x_I - x_s| and the
// overlap delta_I = R + r_I - d > 0, the pair force
//     f_I = k_I delta_I n_I on the particle,  -f_I on the sphere,  n_I = (x_I - x_s) / d,
// is equal and opposite by construction, so the contact conserves linear momentum exactly (to
// round-off); it is central (along the line of centres), so it exerts no torque on the sphere, whose
// spin is therefore not tracked. The stiffness
//     k_I = penalty_scale * rho0 c0^2 h_I
// is the stiffness of a cube of the undeformed material of side h_I (contact frequency sqrt(k/m_I) =
// c0/h_I, within the stable step at scale 1) and is FIXED per particle when the solver initializes:
// the contact is then the gradient of the potential sum 1/2 k_I delta_I^2, exactly conservative
// whatever the law does to the current wave speed; the energy it holds is stored, never lost.
// Friction (option, friction_coefficient mu > 0; 0 by default). On top of the normal force, each pair
// gets a Coulomb force against the tangential part w_t of the relative velocity w = v_I - v_s (at the
// mid-step, where the forces are evaluated):
//     f_t = -min(mu |f_I|, m_I |w_t| / dt) w_t / |w_t|  on the particle,  -f_t on the sphere.
// The cap m_I |w_t| / dt is sticking: the force never does more than stop the relative sliding within
// one step, which keeps the explicit update stable without a regularising slip velocity. Still equal
// and opposite, so linear momentum stays exact; its work, f_t . w dt <= 0, is dissipated and lands in
// the contact energy of the ledger (contact - contact_stored is then the friction loss). The torque
// on the sphere is not applied (its spin is not tracked): zero by symmetry for a normal impact on the
// axis, an approximation otherwise.
// The stable step of the contact: 2 sqrt(m_I / k_I) per particle in contact and 2 sqrt(M / sum k_I)
// for the sphere (velocity Verlet is stable for omega dt < 2), and, so that the sphere cannot pass
// through a particle's contact radius between two steps (contact is detected at positions only), the
// time it takes to travel the smallest contact radius, min r_I / |v_s|. The solver takes the smallest
// of these and the material step before applying its CFL factor.
#include <cstdint>
#include <vector>

#include "solver/conditions.hpp"
#include "solver/particles.hpp"

namespace uhpc::macro {

struct SphereContactOptions {
  double penalty_scale = 1.0;          // k_I = penalty_scale * rho0 c0^2 h_I
  double contact_radius_factor = 0.5;  // r_I = contact_radius_factor * h_I
  double friction_coefficient = 0.0;   // Coulomb mu (0: frictionless)
};

struct RigidSphere {
  double mass_kg = 0.0;
  double radius_m = 0.0;
  Vec3 x{};       // centre, m
  Vec3 v{};       // velocity, m/s
  Vec3 x_prev{};  // centre at the start of the step
  Vec3 force{};   // contact force on the sphere (minus the sum of the forces on the particles), N
  SphereContactOptions contact;

  // Throws std::invalid_argument unless mass, radius, penalty scale and contact radius factor are > 0,
  // the friction coefficient is >= 0 and the state is finite.
  void validate() const;
  double kinetic_energy() const { return 0.5 * mass_kg * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
};

// What one contact evaluation found.
struct SphereContactSums {
  Vec3 force_on_sphere{};            // N
  double stored_energy = 0.0;        // sum 1/2 k_I delta_I^2, J
  double stiffness_sum = 0.0;        // sum of k_I over the particles in contact, N/m
  double critical_step = 0.0;        // s (infinity when nothing touches)
  std::int64_t particles_in_contact = 0;
};

// Penalty stiffness k_I of every particle (n values) for `options`, from the reference density and the
// current (initial) wave speeds in `p`.
void sphere_contact_stiffness(const Particles& p, const SphereContactOptions& options, std::vector<double>& k);

// Writes the contact force of every particle into f_contact (3n; zero where there is no contact) and
// returns the sums. `k` from sphere_contact_stiffness.
// `min_contact_radius` is the smallest r_I (for the travel limit); `dt` the step (friction's sticking cap).
SphereContactSums sphere_contact_forces(const RigidSphere& sphere, const Particles& p, const double* k,
                                        double min_contact_radius, double dt, double* f_contact);

}  // namespace uhpc::macro
