#pragma once
// GMRES, right-preconditioned and without restart, for A x = b. The Newton corrections of the crack
// analysis use it with an earlier factorization of the tangent as the preconditioner M: between Newton
// iterations the tangent changes at the cohesive points only (the bulk is linear), so A M^-1 is the
// identity plus a low-rank term and GMRES converges in about rank + 1 iterations, each a triangular
// solve and a matrix product instead of a numeric factorization. With right preconditioning the
// residual GMRES minimizes is the true one, |b - A x|.
#include <functional>

#include <Eigen/Core>
#include <Eigen/Sparse>

namespace uhpc::micro {

struct GmresResult {
  bool converged = false;
  int iterations = 0;           // products with A (and applications of M^-1)
  double residual_norm = 0.0;   // |b - A x| (from the Arnoldi recurrence)
};

// z = M^-1 v.
using Preconditioner = std::function<void(const Eigen::VectorXd& v, Eigen::VectorXd& z)>;

// Iterates from x = 0 until |b - A x| <= tolerance (absolute) or max_iterations; x is the best
// iterate either way.
GmresResult preconditioned_gmres(const Eigen::SparseMatrix<double>& A, const Preconditioner& precondition,
                                 const Eigen::VectorXd& b, double tolerance, int max_iterations, Eigen::VectorXd& x);

}  // namespace uhpc::micro
