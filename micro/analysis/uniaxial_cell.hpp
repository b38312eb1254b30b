#pragma once
// The microcell's uniaxial tension test of docs/physics.md section 2, elastic (no crack opens): along the
// load axis, u = 0 on the near face and u = e_bar l_mic on the far face (Nitsche, that component
// only; the other component is traction-free there), the two lateral faces and the pores free, and
// the transverse component fixed at the midpoint of the near face (a point penalty; it only removes
// the rigid translation). Homogenized: sigma_bar = far-face reaction / l_mic (per unit thickness),
// E0_bar = sigma_bar / e_bar, the reference modulus of the energy bridging (Psi_0 = 1/2 E0_bar e^2).
#include <cstddef>
#include <string>

#include "cell_geometry.hpp"
#include "cell_mesh.hpp"
#include "elastic_problem.hpp"
#include "rk_galerkin_model.hpp"

namespace uhpc::micro {

struct UniaxialOptions {
  double strain = 1e-4;           // e_bar (linear problem: E0_bar does not depend on it)
  double nitsche_factor = 100.0;  // [choice] beta = factor x E' / h
  RkGalerkinOptions rk;
};

struct UniaxialResult {
  double strain = 0.0;
  double sigma_bar_Pa = 0.0;          // far-face reaction / l_mic
  double E0_bar_Pa = 0.0;             // sigma_bar / e_bar
  double near_face_force_N_m = 0.0;   // reaction on the near face (should be -far; the difference is the
  double far_face_force_N_m = 0.0;    // quadrature's equilibrium error)
  // Force of the transverse point penalty (exact Galerkin: zero, since the loads have no transverse
  // resultant; the Petrov-Galerkin VCI scheme leaves a small one, a measure of its inconsistency).
  double point_force_N_m = 0.0;
  double energy_density_J_m3 = 0.0;   // Psi_bar = strain energy / l_mic^2 (the whole cell, pores included)
  double half_sigma_e_J_m3 = 0.0;     // 1/2 sigma_bar e_bar
  double hill_mandel_relative = 0.0;  // (Psi_bar - 1/2 sigma_bar e_bar) / (1/2 sigma_bar e_bar)
  double far_face_mean_displacement_m = 0.0;  // mean u along the load on the far face (weak BC check)
  std::size_t nodes = 0, dofs = 0, domain_points = 0, boundary_points = 0;
  std::size_t quasi_linear_points = 0;  // RK points evaluated with the regularised moment matrix
  double vci_max_correction = 0.0;
  std::string solver;
  double solver_relative_residual = 0.0;
  double model_s = 0.0, assembly_s = 0.0, solve_s = 0.0;
};

// The elastic problem (for tests and for the cohesive analysis to extend).
ElasticProblem uniaxial_problem(double side_m, LoadAxis axis, double strain, const PlaneStrain& material,
                                double nitsche_factor);

UniaxialResult uniaxial_elastic_response(const CellDiscretization& mesh, double side_m, LoadAxis axis,
                                         const PlaneStrain& material, const UniaxialOptions& options);

}  // namespace uhpc::micro
