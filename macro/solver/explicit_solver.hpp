#pragma once
// The 3D explicit semi-Lagrangian RKPM solver core: one body of particles, one material, walls and
// prescribed velocities. Each step (velocity Verlet, verlet.hpp):
//   1. v += dt/2 a, constraints, x += dt v                                  (integrator)
//   2. RK gradients at the mid-step configuration (x_n + x_n+1)/2 with fresh neighbour lists
//      (StrainConfiguration::Midpoint) or at x_n+1 (End); L_I = sum_J v_J (x) grad Psi_J(x_I)
//   3. constitutive update per particle (stress_update.hpp): rotation, law, volume, bulk viscosity,
//      critical step
//   4. RK gradients at x_n+1 (Midpoint only: End reuses step 2), nodal-integration internal forces,
//      wall and reaction forces, a = f / m
//   5. v += dt/2 a, constraints; energies and momentum; next dt = CFL * min critical step
// Nothing allocates inside steps once the neighbour counts have settled.
#include <cstdint>
#include <vector>

#include "solver/conditions.hpp"
#include "solver/energy.hpp"
#include "solver/internal_force.hpp"
#include "solver/material_set.hpp"
#include "solver/particles.hpp"
#include "solver/second_gradients.hpp"
#include "solver/shape_cache.hpp"
#include "solver/verlet.hpp"
#include "solver/bulk_viscosity.hpp"
#include "uhpc/rk_shape.hpp"

namespace uhpc::macro {

enum class StrainConfiguration : std::uint8_t {
  Midpoint,  // strain rate at (x_n + x_n+1)/2: second order, objective, time-reversible; 2 RK builds/step
  End,       // strain rate at x_n+1: one RK build per step, first order in the configuration
};

enum class Stabilization : std::uint8_t {
  None,  // direct nodal integration
  Nsni,  // naturally stabilized nodal integration (Hillman and Chen 2016), see README.md
};

struct SolverOptions {
  rk::Options rk;              // linear basis, cubic B-spline, quasi-linear regularisation (common defaults)
  double support_factor = 2.0; // a_I = support_factor * h_I
  double cfl = 0.4;            // dt = cfl * min_I critical step (PHYSICS.md: 0.3 - 0.5)
  double fixed_dt_s = 0.0;     // > 0: use this step instead (reversibility studies); must be <= stable
  StrainConfiguration strain_configuration = StrainConfiguration::Midpoint;
  BulkViscosity viscosity;     // {0, 0} switches it off
  Stabilization stabilization = Stabilization::Nsni;
  SecondGradientOptions second_gradients;  // NSNI strain gradients (quadratic implicit second derivatives)
};

class ExplicitSolver {
 public:
  // `particles` must come from Particles::from_body with the density of the material.
  ExplicitSolver(Particles particles, MaterialSet material, const SolverOptions& options);

  void add_wall(const Wall& wall) { walls_.push_back(wall); }
  void add_prescribed_velocity(const PrescribedVelocity& bc) { prescribed_.push_back(bc); }

  // Forces and accelerations at t = 0, initial energies and momentum, the first stable step. Call once
  // after the conditions are set (initial velocities in particles().v).
  void initialize();
  // One step of size dt() (or fixed_dt_s, which is not checked against the stable step). Returns false
  // (the state of the failed step is kept: the last good state is the caller's to save) when a volume
  // became non-positive or a velocity non-finite; failure_particle() then names a particle.
  bool step();

  double time() const { return time_; }
  double dt() const { return options_.fixed_dt_s > 0 ? options_.fixed_dt_s : dt_; }
  double stable_dt() const { return dt_; }
  std::int64_t steps() const { return steps_; }
  const EnergyLedger& ledger() const { return ledger_; }
  const Particles& particles() const { return p_; }
  Particles& particles() { return p_; }
  const MaterialSet& material() const { return material_; }
  const ShapeCache& shapes() const { return shapes_; }  // at the current configuration after a step
  const SolverOptions& options() const { return options_; }
  double wall_force_magnitude() const { return wall_force_; }  // total normal wall force, last step
  std::int64_t failure_particle() const { return failure_; }

  // The physics interface of velocity_verlet_step.
  VerletArrays verlet_arrays() { return {p_.x.data(), p_.x_prev.data(), p_.v.data(), p_.a.data(), 3 * p_.n}; }
  void constrain_velocities();
  void compute_accelerations(double dt);

 private:
  const SecondGradientOptions* second_options() const;  // null without NSNI
  void compute_forces();  // f_int, f_ext and a at the current configuration (shapes_ up to date)
  void update_momentum_and_kinetic();

  Particles p_;
  MaterialSet material_;
  SolverOptions options_;
  std::vector<Wall> walls_;
  std::vector<PrescribedVelocity> prescribed_;
  ShapeCache shapes_;
  InternalForce force_;
  std::vector<double> f_ext_old_;
  EnergyLedger ledger_;
  double time_ = 0.0, dt_ = 0.0, wall_force_ = 0.0;
  std::int64_t steps_ = 0, failure_ = -1;
};

}  // namespace uhpc::macro
