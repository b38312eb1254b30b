#pragma once
// Particle state of the 3D explicit solver as a structure of arrays: each field is one contiguous
// vector (3 or 9 doubles per particle for vectors and tensors, row-major 3x3), so the loops over
// particles stream through memory and vectorise, and a later MPI split is a split of index ranges.
#include <cstddef>
#include <vector>

#include "bodies/particle_body.hpp"

namespace uhpc::macro {

// A field that a step changes and a later step reads must also be listed in copy_evolving_state
// (explicit_solver.cpp), which saves and restores the last good state; constants of the step loop and
// per-step scratch are left out of that copy on purpose.
struct Particles {
  std::size_t n = 0;
  std::vector<double> x;        // current position (3n), m
  std::vector<double> x_prev;   // position at the start of the step (3n)
  std::vector<double> x_mid;    // mid-step configuration where the strain rate is evaluated (3n)
  std::vector<double> v;        // velocity (3n), m/s
  std::vector<double> a;        // acceleration (3n), m/s^2
  std::vector<double> f_int;    // internal force (3n), N
  std::vector<double> f_ext;    // external force: walls and reactions of prescribed velocities (3n), N
  std::vector<double> f_contact;  // force from the rigid sphere (3n), N (kept apart: it is not external)
  std::vector<double> mass;     // lumped mass rho0 V0 (constant), kg
  std::vector<double> volume;   // current volume V_I, m^3
  std::vector<double> volume0;  // reference volume V0_I
  std::vector<double> density;  // current density m_I / V_I, kg/m^3
  std::vector<double> spacing;  // reference nodal spacing h_I (sets the support and the SDEL lambda), m
  std::vector<double> support;  // RK support radius a_I = support_factor * h_I, m
  std::vector<double> stress;   // Cauchy stress from the material law (9n), Pa
  std::vector<double> bulk_q;   // artificial bulk viscosity pressure (n), Pa
  std::vector<double> vel_grad; // velocity gradient L = dv/dx at the particle (9n), 1/s
  std::vector<double> wave_speed;  // current material wave speed c_I (n), m/s
  std::vector<double> work;     // stress work done on the particle so far, sum V sigma : D dt (n), J
  // NSNI (only sized when the stabilization is on): per particle and direction d, the gradient
  // d(sigma)/dx_d of the stabilization stress and d(L)/dx_d, as 3 row-major 3x3 blocks (27n).
  std::vector<double> stress_grad;
  std::vector<double> vel_grad_grad;
  // With a law that splits its stress (eq. 21): stress_grad is the effective gradient and this its
  // split, the one the forces use (27n; empty otherwise).
  std::vector<double> stress_grad_nominal;
  // The gradient the NSNI forces use.
  const std::vector<double>& force_stress_grad() const {
    return stress_grad_nominal.empty() ? stress_grad : stress_grad_nominal;
  }
  // The scale of the NSNI moments (SolverOptions::nsni_coefficient): M_L = scale V_L^(5/3) / 12.
  double nsni_moment_scale = 1.0;

  // Allocates every field for the particles of `body` at rest, with density rho0 and a_I = factor h_I.
  static Particles from_body(const ParticleBody& body, double density_kg_m3, double support_factor);
};

}  // namespace uhpc::macro
