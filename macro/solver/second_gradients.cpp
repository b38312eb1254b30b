#include "solver/second_gradients.hpp"

#include <algorithm>
#include <cmath>

#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // Eigen's 9x9 eigensolver, as in rk_shape.cpp
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace uhpc::macro {

namespace {
using Vec10 = Eigen::Matrix<double, 10, 1>;
using Vec4 = Eigen::Matrix<double, 4, 1>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat4 = Eigen::Matrix<double, 4, 4>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat46 = Eigen::Matrix<double, 4, 6>;

// Quadratic basis at y: 1, y0, y1, y2, then y0y0, y0y1, y0y2, y1y1, y1y2, y2y2.
inline Vec10 monomials(const double* y) {
  Vec10 H;
  H << 1.0, y[0], y[1], y[2], y[0] * y[0], y[0] * y[1], y[0] * y[2], y[1] * y[1], y[1] * y[2], y[2] * y[2];
  return H;
}
}  // namespace

SecondGradientPath second_gradients(const SecondGradientOptions& options, const double* x, const double* nodes,
                                    const double* support, const std::int32_t* nbr, int n, double* hess) {
  double h = 0.0, m00 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double* xk = nodes + 3 * static_cast<std::size_t>(nbr[k]);
    const double a = support[nbr[k]];
    const double r = std::sqrt((x[0] - xk[0]) * (x[0] - xk[0]) + (x[1] - xk[1]) * (x[1] - xk[1]) +
                               (x[2] - xk[2]) * (x[2] - xk[2]));
    hess[6 * k] = kernel_value(options.kernel, r / a).w;  // kernel weight, kept in slot 0 until the end
    m00 += hess[6 * k];
    h = std::max(h, a);
  }
  if (!(m00 > 0.0)) {
    std::fill(hess, hess + 6 * static_cast<std::ptrdiff_t>(n), 0.0);
    return SecondGradientPath::Empty;
  }
  const double inv_h = 1.0 / h;
  auto basis_at = [&](int k) {
    const double* xk = nodes + 3 * static_cast<std::size_t>(nbr[k]);
    const double y[3] = {(x[0] - xk[0]) * inv_h, (x[1] - xk[1]) * inv_h, (x[2] - xk[2]) * inv_h};
    return monomials(y);
  };
  // Moment blocks of P = [1, y] (linear) and Q = [y_a y_b] (quadratic).
  Mat4 Mpp = Mat4::Zero();
  Mat46 Mpq = Mat46::Zero();
  Mat6 Mqq = Mat6::Zero();
  for (int k = 0; k < n; ++k) {
    const double w = hess[6 * k];
    if (w == 0.0) continue;
    const Vec10 H = basis_at(k);
    const Vec4 P = H.head<4>();
    const Vec6 Q = H.tail<6>();
    Mpp.noalias() += w * P * P.transpose();
    Mpq.noalias() += w * P * Q.transpose();
    Mqq.noalias() += w * Q * Q.transpose();
  }
  const Eigen::LDLT<Mat4> lin(Mpp);
  const Mat46 X = lin.solve(Mpq);
  Mat6 S = Mqq - Mpq.transpose() * X;  // what the quadratic monomials add beyond their linear fit

  SecondGradientPath path = SecondGradientPath::Full;
  Eigen::LLT<Mat6> llt(S);
  if (llt.info() != Eigen::Success || !(llt.rcond() >= options.rcond_min)) {
    const Eigen::SelfAdjointEigenSolver<Mat6> eig(S);
    const double floor = options.regularization * std::max(eig.eigenvalues()(5), 0.0);
    for (int k = 0; k < 6 && eig.eigenvalues()(k) < floor; ++k)
      S += (floor - eig.eigenvalues()(k)) * eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose();
    llt.compute(S);
    path = SecondGradientPath::Regularized;
  }
  // Right-hand sides: column m of the six pairs (xx, yy, zz, yz, xz, xy); rows are the quadratic
  // monomials y0y0, y0y1, y0y2, y1y1, y1y2, y2y2.
  Mat6 rhs = Mat6::Zero();
  const double s2 = inv_h * inv_h;
  rhs(0, 0) = 2.0 * s2;
  rhs(3, 1) = 2.0 * s2;
  rhs(5, 2) = 2.0 * s2;
  rhs(4, 3) = s2;
  rhs(2, 4) = s2;
  rhs(1, 5) = s2;
  const Mat6 c = llt.solve(rhs);
  // Linear part from the constraint sum_J Psi_J P_J = 0, then one correction of its round-off defect.
  Mat46 a = -X * c;
  Mat46 defect = Mpp * a + Mpq * c;
  a -= lin.solve(defect);
  for (int k = 0; k < n; ++k) {
    const double w = hess[6 * k];
    if (w == 0.0) {
      for (int m = 0; m < 6; ++m) hess[6 * k + m] = 0.0;
      continue;
    }
    const Vec10 H = basis_at(k);
    const Eigen::Matrix<double, 1, 6> v = w * (H.head<4>().transpose() * a + H.tail<6>().transpose() * c);
    for (int m = 0; m < 6; ++m) hess[6 * k + m] = v(m);
  }
  return path;
}

}  // namespace uhpc::macro
