#pragma once
// Direct sparse solves with SuiteSparse (through Eigen's wrappers): CHOLMOD's supernodal Cholesky
// for a symmetric positive definite K (Galerkin without the VCI correction), UMFPACK's LU otherwise
// (the Petrov-Galerkin VCI stiffness is not symmetric; the cohesive tangents that come next are not
// definite either).
#include <string>

#include <Eigen/Sparse>

namespace uhpc::micro {

struct SparseSolveInfo {
  std::string solver;         // "cholmod" | "umfpack"
  double relative_residual;   // |K d - f| / |f|
};

// Throws uhpc::NumericalError when the factorization fails (singular or, for CHOLMOD, not positive
// definite: the Nitsche factor too small) or the solution is not finite.
Eigen::VectorXd solve_sparse(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f, bool symmetric,
                             SparseSolveInfo* info = nullptr);

}  // namespace uhpc::micro
