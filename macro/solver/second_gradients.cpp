#include "solver/second_gradients.hpp"

#include <algorithm>
#include <cmath>

#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // Eigen's 6x6 eigensolver, as in rk_shape.cpp
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace uhpc::macro {

namespace {

// ---- small fixed-size dense algebra (the sizes are compile-time constants: fully unrolled, no
// allocation, none of Eigen's blocked triangular-solve machinery for a handful of numbers) ----

// In-place Cholesky A = L L^T of a symmetric N x N matrix (lower triangle used). False when A is not
// numerically positive definite.
template <int N>
bool cholesky(double (&A)[N][N]) {
  for (int j = 0; j < N; ++j) {
    double d = A[j][j];
    for (int k = 0; k < j; ++k) d -= A[j][k] * A[j][k];
    if (!(d > 0.0)) return false;
    const double l = std::sqrt(d);
    A[j][j] = l;
    const double inv = 1.0 / l;
    for (int i = j + 1; i < N; ++i) {
      double s = A[i][j];
      for (int k = 0; k < j; ++k) s -= A[i][k] * A[j][k];
      A[i][j] = s * inv;
    }
  }
  return true;
}

// Solves L L^T X = B in place for the M columns of B (N x M, row-major).
template <int N, int M>
void cholesky_solve(const double (&L)[N][N], double (&B)[N][M]) {
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < i; ++k)
      for (int c = 0; c < M; ++c) B[i][c] -= L[i][k] * B[k][c];
    const double inv = 1.0 / L[i][i];
    for (int c = 0; c < M; ++c) B[i][c] *= inv;
  }
  for (int i = N - 1; i >= 0; --i) {
    for (int k = i + 1; k < N; ++k)
      for (int c = 0; c < M; ++c) B[i][c] -= L[k][i] * B[k][c];
    const double inv = 1.0 / L[i][i];
    for (int c = 0; c < M; ++c) B[i][c] *= inv;
  }
}

// Quadratic monomials y_a y_b in the order y0y0, y0y1, y0y2, y1y1, y1y2, y2y2.
inline void quadratics(const double* y, double* q) {
  q[0] = y[0] * y[0];
  q[1] = y[0] * y[1];
  q[2] = y[0] * y[2];
  q[3] = y[1] * y[1];
  q[4] = y[1] * y[2];
  q[5] = y[2] * y[2];
}

// Weighted moments of the quadratic basis [1, y, q]: everything sum_J w_J H_J H_J^T needs.
struct QuadMoments {
  double m00 = 0.0;
  double m1[3] = {};     // sum w y_a
  double m2[6] = {};     // sum w q_b (= sum w y_a y_b: also the linear second moments)
  double m3[3][6] = {};  // sum w y_a q_b
  double m4[6][6] = {};  // sum w q_b q_c
};

// The neighbourhood of one point in structure-of-arrays form: H[r][k] the 10 monomials [1, y, q] of
// node k and WH[r][k] = w_k H[r][k]. Every per-node loop below runs over k innermost on contiguous
// arrays (vectorised; the moment sums are dot products held in registers instead of 49
// accumulators updated through memory per node).
constexpr int kMaxNodes = 512;
struct Neighbourhood {
  int n = 0;
  double h = 0.0, inv_h = 0.0, m00 = 0.0;
  int stride = 0;  // n rounded up to 8: the 20 rows are packed (rows kMaxNodes apart would all fall in
                   // the same L1 sets)
  alignas(64) double Hbuf[10 * kMaxNodes];
  alignas(64) double WHbuf[10 * kMaxNodes];
  double* H(int r) { return Hbuf + r * stride; }
  double* WH(int r) { return WHbuf + r * stride; }
  const double* H(int r) const { return Hbuf + r * stride; }
  const double* WH(int r) const { return WHbuf + r * stride; }

  // Kernel weights and the scale h (the largest support radius) as rk_shape computes them; false
  // when no node covers x (all weights zero).
  // Quadratic false: rows 0..3 only (the linear basis).
  template <bool Quadratic = true>
  bool build(KernelType kernel, const double* x, const double* nodes, const double* support,
             const std::int32_t* nbr, int count) {
    n = count;
    stride = (count + 7) & ~7;
    h = 0.0;
    m00 = 0.0;
    for (int k = 0; k < n; ++k) {
      const double* xk = nodes + 3 * static_cast<std::size_t>(nbr[k]);
      const double a = support[nbr[k]];
      const double d0 = x[0] - xk[0], d1 = x[1] - xk[1], d2 = x[2] - xk[2];
      H(1)[k] = d0;
      H(2)[k] = d1;
      H(3)[k] = d2;
      const double w = kernel_value(kernel, std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) / a).w;
      WH(0)[k] = w;
      m00 += w;
      h = std::max(h, a);
    }
    if (!(m00 > 0.0)) return false;
    inv_h = 1.0 / h;
    for (int k = 0; k < n; ++k) {
      const double y0 = H(1)[k] * inv_h, y1 = H(2)[k] * inv_h, y2 = H(3)[k] * inv_h, w = WH(0)[k];
      H(0)[k] = 1.0;
      H(1)[k] = y0;
      H(2)[k] = y1;
      H(3)[k] = y2;
      if constexpr (Quadratic) {
        H(4)[k] = y0 * y0;
        H(5)[k] = y0 * y1;
        H(6)[k] = y0 * y2;
        H(7)[k] = y1 * y1;
        H(8)[k] = y1 * y2;
        H(9)[k] = y2 * y2;
      }
      for (int r = 1; r < (Quadratic ? 10 : 4); ++r) WH(r)[k] = w * H(r)[k];
    }
    return true;
  }

  double dot(int r, int s) const {
    double acc0 = 0.0, acc1 = 0.0, acc2 = 0.0, acc3 = 0.0;
    int k = 0;
    for (; k + 4 <= n; k += 4) {
      acc0 += WH(r)[k] * H(s)[k];
      acc1 += WH(r)[k + 1] * H(s)[k + 1];
      acc2 += WH(r)[k + 2] * H(s)[k + 2];
      acc3 += WH(r)[k + 3] * H(s)[k + 3];
    }
    for (; k < n; ++k) acc0 += WH(r)[k] * H(s)[k];
    return (acc0 + acc1) + (acc2 + acc3);
  }

  QuadMoments moments() const {
    QuadMoments m;
    m.m00 = m00;
    for (int a = 0; a < 3; ++a) m.m1[a] = dot(0, 1 + a);
    for (int b = 0; b < 6; ++b) m.m2[b] = dot(0, 4 + b);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 6; ++b) m.m3[a][b] = dot(1 + a, 4 + b);
    for (int b = 0; b < 6; ++b)
      for (int c = b; c < 6; ++c) m.m4[b][c] = m.m4[c][b] = dot(4 + b, 4 + c);
    return m;
  }

  // hess[6k + m] = w_k H_k^T G(:, m), node by node with the six sums in registers.
  void second_output(const double (&G)[10][6], double* hess) const {
    for (int k = 0; k < n; ++k) {
      double acc[6];
      for (int m = 0; m < 6; ++m) acc[m] = G[0][m] * WH(0)[k];
      for (int r = 1; r < 10; ++r) {
        const double wh = WH(r)[k];
        for (int m = 0; m < 6; ++m) acc[m] += G[r][m] * wh;
      }
      for (int m = 0; m < 6; ++m) hess[6 * k + m] = acc[m];
    }
  }
};

// Index of y_a y_b in the quadratic monomials above.
constexpr int quad_index(int a, int b) {
  const int i = a < b ? a : b, j = a < b ? b : a;
  return i == 0 ? j : (i == 1 ? 2 + j : 5);
}

// Coefficients of the second derivatives from the moments: G (10 x 6, rows [1, y, q], columns the
// pairs xx, yy, zz, yz, xz, xy) with Psi^(m)_J = w_J H_J^T G(:, m). See second_gradients.hpp.
SecondGradientPath second_coefficients(const SecondGradientOptions& options, const QuadMoments& mom, double inv_h,
                                       double (&G)[10][6]) {
  // Mpp = [[m00, m1^T], [m1, M2]] (linear block), Mpq = [[m2^T], [m3]] (4 x 6), Mqq = m4.
  double Lp[4][4];
  Lp[0][0] = mom.m00;
  for (int a = 0; a < 3; ++a) {
    Lp[1 + a][0] = mom.m1[a];
    for (int b = 0; b <= a; ++b) Lp[1 + a][1 + b] = mom.m2[quad_index(a, b)];
  }
  double Mpq[4][6];
  for (int b = 0; b < 6; ++b) {
    Mpq[0][b] = mom.m2[b];
    for (int a = 0; a < 3; ++a) Mpq[1 + a][b] = mom.m3[a][b];
  }
  double Mpp[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j <= i; ++j) Mpp[i][j] = Mpp[j][i] = Lp[i][j];
  const bool linear_ok = cholesky<4>(Lp);

  double S[6][6];
  double X[4][6];
  if (linear_ok) {
    for (int i = 0; i < 4; ++i)
      for (int b = 0; b < 6; ++b) X[i][b] = Mpq[i][b];
    cholesky_solve<4, 6>(Lp, X);
  } else {
    // The linear block itself is singular (a degenerate neighbourhood): least-squares solve with
    // Eigen's pivoted LDLT, as before.
    Eigen::Matrix4d P;
    Eigen::Matrix<double, 4, 6> Q;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) P(i, j) = Mpp[i][j];
      for (int b = 0; b < 6; ++b) Q(i, b) = Mpq[i][b];
    }
    const Eigen::Matrix<double, 4, 6> Xe = Eigen::LDLT<Eigen::Matrix4d>(P).solve(Q);
    for (int i = 0; i < 4; ++i)
      for (int b = 0; b < 6; ++b) X[i][b] = Xe(i, b);
  }
  for (int b = 0; b < 6; ++b)
    for (int c = 0; c < 6; ++c) {
      double s = mom.m4[b][c];
      for (int i = 0; i < 4; ++i) s -= Mpq[i][b] * X[i][c];
      S[b][c] = s;
    }
  for (int b = 0; b < 6; ++b)  // exactly symmetric
    for (int c = 0; c < b; ++c) S[b][c] = S[c][b] = 0.5 * (S[b][c] + S[c][b]);
  // When the quadratic monomials add nothing beyond the linear fit (a fragment whose few points fit a
  // linear field exactly: S is zero but for round-off), lifting S relative to its own largest
  // eigenvalue would turn round-off into second derivatives of order 1/(eps h^2): there are none.
  double trace_S = 0.0, trace_q = 0.0;
  for (int b = 0; b < 6; ++b) {
    trace_S += S[b][b];
    trace_q += mom.m4[b][b];
  }
  if (!(trace_S >= options.rcond_min * trace_q)) {
    for (int r = 0; r < 10; ++r)
      for (int m = 0; m < 6; ++m) G[r][m] = 0.0;
    return SecondGradientPath::Empty;
  }

  SecondGradientPath path = SecondGradientPath::Full;
  double Ls[6][6];
  auto copy_S = [&]() {
    for (int b = 0; b < 6; ++b)
      for (int c = 0; c < 6; ++c) Ls[b][c] = S[b][c];
  };
  auto lift = [&](bool& lifted) {
    Eigen::Matrix<double, 6, 6> Se;
    for (int b = 0; b < 6; ++b)
      for (int c = 0; c < 6; ++c) Se(b, c) = S[b][c];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(Se);
    const double floor = options.regularization * std::max(eig.eigenvalues()(5), 0.0);
    lifted = false;
    for (int k = 0; k < 6 && eig.eigenvalues()(k) < floor; ++k) {
      Se += (floor - eig.eigenvalues()(k)) * eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose();
      lifted = true;
    }
    for (int b = 0; b < 6; ++b)
      for (int c = 0; c < 6; ++c) S[b][c] = Se(b, c);
  };
  // Right-hand sides: the second derivatives of the quadratic monomials (scaled by 1/h^2); column m
  // of c is scale[m] times column row[m] of S^-1.
  double c[6][6];
  const double s2 = inv_h * inv_h;
  constexpr int rhs_row[6] = {0, 3, 5, 4, 2, 1};  // xx <- y0y0, yy <- y1y1, zz <- y2y2, yz <- y1y2, xz <- y0y2, xy <- y0y1
  const double rhs_scale[6] = {2.0 * s2, 2.0 * s2, 2.0 * s2, s2, s2, s2};
  auto solve_c = [&]() {
    for (int b = 0; b < 6; ++b)
      for (int m = 0; m < 6; ++m) c[b][m] = 0.0;
    for (int m = 0; m < 6; ++m) c[rhs_row[m]][m] = rhs_scale[m];
    cholesky_solve<6, 6>(Ls, c);
  };
  auto zero = [&]() {
    for (int r = 0; r < 10; ++r)
      for (int m = 0; m < 6; ++m) G[r][m] = 0.0;
    return SecondGradientPath::Regularized;
  };
  if (options.continuous_regularization) {
    // Lift every eigenvalue below floor = regularization * lambda_max: S^-1 is then a continuous
    // function of the configuration, bounded by 1 / floor. Nothing is lifted when lambda_min >=
    // regularization * u for an upper bound u of lambda_max (u = min(tr S, ||S||_inf)); two cheap
    // sufficient tests of that, then the eigendecomposition. Whichever decides, a point that needs no
    // lift gets the plain factorization of S, so the tests only save time.
    double trace = 0.0, row_max = 0.0;
    for (int b = 0; b < 6; ++b) {
      trace += S[b][b];
      double row = 0.0;
      for (int cc = 0; cc < 6; ++cc) row += std::abs(S[b][cc]);
      row_max = std::max(row_max, row);
    }
    const double bound = options.regularization * std::min(trace, row_max);
    copy_S();
    bool accepted = false;
    if (cholesky<6>(Ls)) {
      solve_c();
      // lambda_min(S) >= 1 / ||S^-1||_1, the columns of S^-1 being those of c over their scales.
      double inv_norm = 0.0;
      for (int m = 0; m < 6; ++m) {
        double col = 0.0;
        for (int b = 0; b < 6; ++b) col += std::abs(c[b][m]);
        inv_norm = std::max(inv_norm, col / rhs_scale[m]);
      }
      accepted = bound * inv_norm <= 1.0;
      if (!accepted) {  // exact test: S - bound I positive definite
        double shifted[6][6];
        for (int b = 0; b < 6; ++b)
          for (int cc = 0; cc < 6; ++cc) shifted[b][cc] = S[b][cc] - (b == cc ? bound : 0.0);
        accepted = cholesky<6>(shifted);
      }
    }
    if (!accepted) {
      bool lifted = false;
      lift(lifted);
      if (lifted) path = SecondGradientPath::Regularized;
      copy_S();
      if (!cholesky<6>(Ls)) return zero();  // S = 0 (no quadratic information at all)
      solve_c();
    }
  } else {
    // The original criterion: regularise only when the 1-norm condition estimate is below rcond_min.
    Eigen::Matrix<double, 6, 6> Se;
    for (int b = 0; b < 6; ++b)
      for (int cc = 0; cc < 6; ++cc) Se(b, cc) = S[b][cc];
    const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(Se);
    if (llt.info() != Eigen::Success || !(llt.rcond() >= options.rcond_min)) {
      bool lifted = false;
      lift(lifted);
      path = SecondGradientPath::Regularized;
    }
    copy_S();
    if (!cholesky<6>(Ls)) return zero();
    solve_c();
  }
  // Linear part from the constraint sum_J Psi_J P_J = 0: a = -X c, then one correction of its
  // round-off defect Mpp a + Mpq c.
  double a[4][6];
  for (int i = 0; i < 4; ++i)
    for (int m = 0; m < 6; ++m) {
      double s = 0.0;
      for (int b = 0; b < 6; ++b) s -= X[i][b] * c[b][m];
      a[i][m] = s;
    }
  double defect[4][6];
  for (int i = 0; i < 4; ++i)
    for (int m = 0; m < 6; ++m) {
      double s = 0.0;
      for (int j = 0; j < 4; ++j) s += Mpp[i][j] * a[j][m];
      for (int b = 0; b < 6; ++b) s += Mpq[i][b] * c[b][m];
      defect[i][m] = s;
    }
  if (linear_ok) {
    cholesky_solve<4, 6>(Lp, defect);
  } else {
    Eigen::Matrix4d P;
    Eigen::Matrix<double, 4, 6> D;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) P(i, j) = Mpp[i][j];
      for (int m = 0; m < 6; ++m) D(i, m) = defect[i][m];
    }
    const Eigen::Matrix<double, 4, 6> De = Eigen::LDLT<Eigen::Matrix4d>(P).solve(D);
    for (int i = 0; i < 4; ++i)
      for (int m = 0; m < 6; ++m) defect[i][m] = De(i, m);
  }
  for (int i = 0; i < 4; ++i)
    for (int m = 0; m < 6; ++m) G[i][m] = a[i][m] - defect[i][m];
  for (int b = 0; b < 6; ++b)
    for (int m = 0; m < 6; ++m) G[4 + b][m] = c[b][m];
  // The last guard of a degenerate neighbourhood the tests above let through: none rather than NaN.
  for (int r = 0; r < 10; ++r)
    for (int m = 0; m < 6; ++m)
      if (!std::isfinite(G[r][m])) {
        for (int rr = 0; rr < 10; ++rr)
          for (int mm = 0; mm < 6; ++mm) G[rr][mm] = 0.0;
        return SecondGradientPath::Empty;
      }
  return path;
}

// More than kMaxNodes nodes (never at the supports in use; kept for generality): the same algebra
// node by node, the kernel weights kept in hess[6k] until the output.
SecondGradientPath second_gradients_large(const SecondGradientOptions& options, const double* x, const double* nodes,
                                          const double* support, const std::int32_t* nbr, int n, double* hess) {
  double h = 0.0, m00 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double* xk = nodes + 3 * static_cast<std::size_t>(nbr[k]);
    const double a = support[nbr[k]];
    const double r = std::sqrt((x[0] - xk[0]) * (x[0] - xk[0]) + (x[1] - xk[1]) * (x[1] - xk[1]) +
                               (x[2] - xk[2]) * (x[2] - xk[2]));
    hess[6 * k] = kernel_value(options.kernel, r / a).w;
    m00 += hess[6 * k];
    h = std::max(h, a);
  }
  if (!(m00 > 0.0)) {
    std::fill(hess, hess + 6 * static_cast<std::ptrdiff_t>(n), 0.0);
    return SecondGradientPath::Empty;
  }
  const double inv_h = 1.0 / h;
  auto basis_at = [&](int k, double* H) {
    const double* xk = nodes + 3 * static_cast<std::size_t>(nbr[k]);
    H[0] = 1.0;
    for (int d = 0; d < 3; ++d) H[1 + d] = (x[d] - xk[d]) * inv_h;
    quadratics(H + 1, H + 4);
  };
  QuadMoments mom;
  mom.m00 = m00;
  for (int k = 0; k < n; ++k) {
    const double w = hess[6 * k];
    double H[10];
    basis_at(k, H);
    for (int a = 0; a < 3; ++a) mom.m1[a] += w * H[1 + a];
    for (int b = 0; b < 6; ++b) {
      mom.m2[b] += w * H[4 + b];
      for (int a = 0; a < 3; ++a) mom.m3[a][b] += w * H[1 + a] * H[4 + b];
      for (int c = 0; c < 6; ++c) mom.m4[b][c] += w * H[4 + b] * H[4 + c];
    }
  }
  double G[10][6];
  const SecondGradientPath path = second_coefficients(options, mom, inv_h, G);
  for (int k = 0; k < n; ++k) {
    const double w = hess[6 * k];
    double H[10];
    basis_at(k, H);
    for (int m = 0; m < 6; ++m) {
      double v = 0.0;
      for (int r = 0; r < 10; ++r) v += H[r] * G[r][m];
      hess[6 * k + m] = w * v;
    }
  }
  return path;
}

// RK shape functions and first gradients, linear basis, from the weights and moments of `nb`
// (m1 = sum w y, m2 = sum w y_a y_b in quadratic order); false (nothing written) where rk_shape would
// not take its full path.
bool linear_shapes(const rk::Options& rk_options, const Neighbourhood& nb, const double* m1, const double* m2,
                   double* psi, double* grad, rk::PointResult& result) {
  const double m00 = nb.m00, inv_h = nb.inv_h;
  const int n = nb.n;
  // First gradients, linear basis, rk_shape.cpp's full path: constant eliminated, S = the weighted
  // covariance of y, S c_0 = -mean, S c_i = -(1/h) e_i.
  double mean[3], S3[3][3];
  for (int a = 0; a < 3; ++a) mean[a] = m1[a] / m00;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) S3[a][b] = m2[quad_index(a, b)] - m00 * mean[a] * mean[b];
  // rk_shape takes its full path when Eigen's 1-norm estimate of rcond(S) >= rcond_min. The estimate
  // bounds ||S^-1||_1 from below, so the exact rcond (from the explicit inverse, cheap at 3 x 3) is a
  // lower bound of it: exact >= rcond_min gives the same decision; anything else goes to rk_shape.
  double L3[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) L3[a][b] = S3[a][b];
  if (!cholesky<3>(L3)) return false;
  double inv[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  cholesky_solve<3, 3>(L3, inv);
  double norm = 0.0, inv_norm = 0.0;
  for (int b = 0; b < 3; ++b) {
    norm = std::max(norm, std::abs(S3[0][b]) + std::abs(S3[1][b]) + std::abs(S3[2][b]));
    inv_norm = std::max(inv_norm, std::abs(inv[0][b]) + std::abs(inv[1][b]) + std::abs(inv[2][b]));
  }
  const double rcond = 1.0 / (norm * inv_norm);
  if (!(rcond >= rk_options.rcond_min)) return false;  // maybe quasi-linear or fallback: rk_shape decides
  result.path = rk::Path::Full;
  result.basis = rk::Basis::Linear;
  result.rcond = rcond;  // exact (rk_shape reports Eigen's estimate, >= this)
  // Psi_k = w_k (1/m00 + (y_k - mean)^T c_0), grad_k,i = w_k (y_k - mean)^T c_i: coefficients of w_k
  // y_k,a (WH rows 1..3) and of w_k.
  double coef[3][4], shift[4];
  for (int a = 0; a < 3; ++a) {
    coef[a][0] = -(inv[a][0] * mean[0] + inv[a][1] * mean[1] + inv[a][2] * mean[2]);
    for (int i = 0; i < 3; ++i) coef[a][1 + i] = -inv_h * inv[a][i];
  }
  for (int c = 0; c < 4; ++c) shift[c] = -(mean[0] * coef[0][c] + mean[1] * coef[1][c] + mean[2] * coef[2][c]);
  shift[0] += 1.0 / m00;
  for (int k = 0; k < n; ++k)
    psi[k] = shift[0] * nb.WH(0)[k] + coef[0][0] * nb.WH(1)[k] + coef[1][0] * nb.WH(2)[k] + coef[2][0] * nb.WH(3)[k];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < n; ++k)
      grad[3 * k + i] = shift[1 + i] * nb.WH(0)[k] + coef[0][1 + i] * nb.WH(1)[k] + coef[1][1 + i] * nb.WH(2)[k] +
                        coef[2][1 + i] * nb.WH(3)[k];

  return true;
}

}  // namespace

SecondGradientPath second_gradients(const SecondGradientOptions& options, const double* x, const double* nodes,
                                    const double* support, const std::int32_t* nbr, int n, double* hess) {
  if (n > kMaxNodes) return second_gradients_large(options, x, nodes, support, nbr, n, hess);
  Neighbourhood nb;
  // Fewer than four points (a fragment flying off alone) cannot carry even the linear basis in 3D.
  if (n < 4 || !nb.build(options.kernel, x, nodes, support, nbr, n)) {
    std::fill(hess, hess + 6 * static_cast<std::ptrdiff_t>(n), 0.0);
    return SecondGradientPath::Empty;
  }
  double G[10][6];
  const SecondGradientPath path = second_coefficients(options, nb.moments(), nb.inv_h, G);
  nb.second_output(G, hess);
  return path;
}

SecondGradientPath shape_and_second_gradients(const rk::Options& rk_options, const SecondGradientOptions& options,
                                              const double* x, const double* nodes, const double* support,
                                              const std::int32_t* nbr, int n, double* psi, double* grad,
                                              double* hess, rk::PointResult& result) {
  const bool fusable = rk_options.basis == rk::Basis::Linear && rk_options.gradients &&
                       rk_options.derivatives == rk::Derivatives::Implicit && rk_options.kernel == options.kernel &&
                       n <= kMaxNodes && n >= 4;
  auto separate = [&]() {
    result = rk::evaluate<3>(rk_options, x, nodes, support, nbr, n, psi, grad);
    return second_gradients(options, x, nodes, support, nbr, n, hess);
  };
  if (!fusable) return separate();
  Neighbourhood nb;
  if (!nb.build(options.kernel, x, nodes, support, nbr, n)) return separate();  // Empty: their zeros
  const QuadMoments mom = nb.moments();
  const double inv_h = nb.inv_h;
  if (!linear_shapes(rk_options, nb, mom.m1, mom.m2, psi, grad, result)) return separate();

  double G[10][6];
  const SecondGradientPath path = second_coefficients(options, mom, inv_h, G);
  nb.second_output(G, hess);
  return path;
}

rk::PointResult shape_gradients(const rk::Options& rk_options, const double* x, const double* nodes,
                                const double* support, const std::int32_t* nbr, int n, double* psi, double* grad) {
  rk::PointResult result;
  if (rk_options.basis != rk::Basis::Linear || !rk_options.gradients ||
      rk_options.derivatives != rk::Derivatives::Implicit || n > kMaxNodes)
    return rk::evaluate<3>(rk_options, x, nodes, support, nbr, n, psi, grad);
  Neighbourhood nb;
  if (!nb.build<false>(rk_options.kernel, x, nodes, support, nbr, n))
    return rk::evaluate<3>(rk_options, x, nodes, support, nbr, n, psi, grad);
  double m1[3], m2[6];
  for (int a = 0; a < 3; ++a) m1[a] = nb.dot(0, 1 + a);
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) m2[quad_index(a, b)] = nb.dot(1 + a, 1 + b);
  if (!linear_shapes(rk_options, nb, m1, m2, psi, grad, result))
    return rk::evaluate<3>(rk_options, x, nodes, support, nbr, n, psi, grad);
  return result;
}

}  // namespace uhpc::macro
