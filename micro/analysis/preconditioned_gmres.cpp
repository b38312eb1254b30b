#include "preconditioned_gmres.hpp"

#include <cmath>
#include <vector>

namespace uhpc::micro {

GmresResult preconditioned_gmres(const Eigen::SparseMatrix<double>& A, const Preconditioner& precondition,
                                 const Eigen::VectorXd& b, double tolerance, int max_iterations, Eigen::VectorXd& x) {
  GmresResult res;
  const Eigen::Index n = b.size();
  x = Eigen::VectorXd::Zero(n);
  const double beta = b.norm();
  res.residual_norm = beta;
  if (beta <= tolerance) {
    res.converged = true;
    return res;
  }
  const int m = std::max(max_iterations, 1);
  // V: the Arnoldi basis; Z = M^-1 V (kept, so the solution needs no further application of M^-1).
  Eigen::MatrixXd V(n, m + 1), Z(n, m);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
  std::vector<double> cs(m), sn(m);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(m + 1);  // the rotated right-hand side beta e_1
  g[0] = beta;
  V.col(0) = b / beta;
  Eigen::VectorXd z(n), w(n);
  int k = 0;
  for (; k < m; ++k) {
    precondition(V.col(k), z);
    Z.col(k) = z;
    w.noalias() = A * z;
    // Modified Gram-Schmidt, twice (the basis must stay orthogonal to round-off for the residual
    // estimate to be the true residual).
    for (int pass = 0; pass < 2; ++pass)
      for (int i = 0; i <= k; ++i) {
        const double h = V.col(i).dot(w);
        H(i, k) += h;
        w -= h * V.col(i);
      }
    H(k + 1, k) = w.norm();
    if (H(k + 1, k) > 0.0) V.col(k + 1) = w / H(k + 1, k);
    // Apply the earlier rotations to the new column, then the one that zeroes H(k+1, k).
    for (int i = 0; i < k; ++i) {
      const double t = cs[i] * H(i, k) + sn[i] * H(i + 1, k);
      H(i + 1, k) = -sn[i] * H(i, k) + cs[i] * H(i + 1, k);
      H(i, k) = t;
    }
    const double r = std::hypot(H(k, k), H(k + 1, k));
    cs[k] = r > 0.0 ? H(k, k) / r : 1.0;
    sn[k] = r > 0.0 ? H(k + 1, k) / r : 0.0;
    H(k, k) = r;
    H(k + 1, k) = 0.0;
    g[k + 1] = -sn[k] * g[k];
    g[k] = cs[k] * g[k];
    res.residual_norm = std::abs(g[k + 1]);
    if (res.residual_norm <= tolerance || !(H(k, k) > 0.0)) {
      ++k;
      break;
    }
  }
  res.iterations = k;
  res.converged = res.residual_norm <= tolerance;
  // y = H^-1 g on the leading k x k triangle, x = Z y.
  const Eigen::VectorXd y = H.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
  if (!y.allFinite()) {
    res.converged = false;
    x.setZero();
    return res;
  }
  x.noalias() = Z.leftCols(k) * y;
  return res;
}

}  // namespace uhpc::micro
