#pragma once
// Energy and momentum accounts of a run, updated every step.
//   kinetic      sum 1/2 m v^2 at the end of the step
//   internal     integral of the stress power sum V sigma : D dt plus the NSNI stabilization power
//   stabilization   the NSNI part of `internal`; stabilization_stored of it is held by the gradient
//                stresses now (sum M/2 sigma_,d : C^-1 : sigma_,d with the law's moduli), the rest is
//                dissipated by their return
//   material_stored   elastic (free) energy the laws hold now, sum V Law::stored_energy
//   material_dissipated   the rest of the material's stress work: internal - stabilization -
//                material_stored, dissipated by the laws; of it plastic, crushing and opening are what the laws
//                book (Law::dissipation), released() the remainder: energy a law gave up without
//                booking it (damage: the tension released by d+, the drop of the cutoff)
//   viscous      work of the artificial bulk viscosity (dissipated)
//   external     work of the external forces (walls, reactions of prescribed velocities)
//   contact      energy taken by the sphere contact: minus the work of the contact forces on the
//                particles and the sphere, booked kick by kick (the kinetic energy each half kick of
//                the contact forces gives, exactly); the penalty is conservative, so for it this is the
//                energy held in its springs up to the integrator's error; the kinematic contact stores
//                nothing, so for it this is what its impacts dissipate
//   contact_stored  sum 1/2 k delta^2 at the end of the step (the exact potential, for comparison)
// kinetic and momentum include the rigid sphere (kinetic_sphere, momentum_sphere are its parts).
// Balance: kinetic + internal + viscous + contact - external = initial kinetic (+ initial internal,
// zero here).
#include <array>

namespace uhpc::macro {

struct EnergyLedger {
  double kinetic = 0.0;
  double kinetic_initial = 0.0;
  double internal = 0.0;
  double stabilization = 0.0;  // NSNI part of `internal`
  double stabilization_stored = 0.0;
  double material_stored = 0.0;
  double material_dissipated = 0.0;
  double plastic = 0.0;
  double crushing = 0.0;
  double opening = 0.0;
  double viscous = 0.0;
  double external = 0.0;
  double contact = 0.0;
  double contact_stored = 0.0;
  double kinetic_sphere = 0.0;
  std::array<double, 3> momentum_sphere{};
  std::array<double, 3> momentum{};
  std::array<double, 3> momentum_initial{};
  std::array<double, 3> external_impulse{};

  double released() const { return material_dissipated - plastic - crushing - opening; }
  double stabilization_dissipated() const { return stabilization - stabilization_stored; }
  double balance_error() const { return kinetic + internal + viscous + contact - external - kinetic_initial; }
};

}  // namespace uhpc::macro
