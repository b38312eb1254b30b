#pragma once
// Solving an ElasticProblem on an RkGalerkinModel, and what is measured on the solution: fields at
// sample points, the consistent Nitsche reaction on a boundary part, the strain energy.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "elastic_problem.hpp"
#include "rk_galerkin_model.hpp"
#include "sparse_solver.hpp"

namespace uhpc::micro {

struct ElasticSolution {
  Eigen::VectorXd d;  // nodal coefficients (not nodal displacements: RK functions do not interpolate)
  SparseSolveInfo solve;
  double assembly_s = 0.0;
  double solve_s = 0.0;
};

ElasticSolution solve_elastic(const RkGalerkinModel& model, const ElasticProblem& problem);

struct PointField {
  std::array<double, 2> u;
  std::array<double, 3> strain;  // xx, yy, engineering xy (implicit gradients)
  std::array<double, 3> stress;  // xx, yy, xy (plane strain; sigma_zz = nu (sxx + syy) not stored)
};

// Fields at every point of `points` (from sample_points or the model's own point sets).
std::vector<PointField> fields_at(const PointSet& points, const Eigen::VectorXd& d, const PlaneStrain& material);

// Force per unit thickness that the boundary part exerts on the body, from the Nitsche flux
// int P (t(u_h) - beta (u_h - g)) over the prescribed components plus the tractions of the free ones.
std::array<double, 2> boundary_force(const RkGalerkinModel& model, const ElasticProblem& problem,
                                     const Eigen::VectorXd& d, BoundaryPart part);

// 1/2 int eps : D : eps over the domain (trial strains), per unit thickness.
double strain_energy(const RkGalerkinModel& model, const Eigen::VectorXd& d, const PlaneStrain& material);

}  // namespace uhpc::micro
