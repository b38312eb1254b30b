#pragma once
// Assembly of the elastic system K d = f on the RK Galerkin model: the domain stiffness
// sum_q B~_I^T D B_J w_q (B~ the VCI-corrected test gradients, B the implicit trial gradients), the
// Nitsche terms and tractions on the boundary points, and the point penalties.
//
// The sparsity is fixed first (nodes I and J couple when some integration point lies in both
// supports), then the values are summed in place: the domain part in parallel over columns (trial
// node J owns column J, so threads never write the same entry and nothing is allocated in the loop).
#include <Eigen/Sparse>

#include "elastic_problem.hpp"
#include "rk_galerkin_model.hpp"

namespace uhpc::micro {

struct LinearSystem {
  Eigen::SparseMatrix<double> K;  // 2n x 2n, column-major, DOF 2I + component
  Eigen::VectorXd f;
  bool symmetric = true;          // false with the VCI (Petrov-Galerkin) correction
};

// `constraints` holds the shape functions at problem.points (sample_points), in the same order.
LinearSystem assemble_elastic_system(const RkGalerkinModel& model, const ElasticProblem& problem,
                                     const PointSet& constraints);

// beta of Nitsche's method on boundary segment s: factor x E' / (mean spacing of its two nodes).
double nitsche_beta(const RkGalerkinModel& model, const ElasticProblem& problem, std::size_t segment);

}  // namespace uhpc::micro
