#include "sparse_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

#include "uhpc/errors.hpp"

namespace uhpc::micro {

Eigen::VectorXd solve_sparse(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f, bool symmetric,
                             SparseSolveInfo* info) {
  Eigen::VectorXd d;
  std::string name;
  if (symmetric) {
    name = "cholmod";
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt(K);
    if (llt.info() != Eigen::Success)
      throw NumericalError("CHOLMOD: the stiffness matrix is not positive definite (rigid mode left, or the "
                           "Nitsche factor too small)");
    d = llt.solve(f);
  } else {
    name = "umfpack";
    Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu(K);
    if (lu.info() != Eigen::Success)
      throw NumericalError("UMFPACK: the stiffness matrix is singular (a rigid mode is not constrained)");
    d = lu.solve(f);
  }
  if (!d.allFinite()) throw NumericalError(name + ": the solution is not finite");
  if (info) {
    info->solver = name;
    const double fn = f.norm();
    info->relative_residual = (K * d - f).norm() / (fn > 0.0 ? fn : 1.0);
  }
  return d;
}

}  // namespace uhpc::micro
