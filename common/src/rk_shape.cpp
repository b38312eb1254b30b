#include "uhpc/rk_shape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

// GCC 12 reports a false -Wmaybe-uninitialized inside Eigen's tridiagonalization (9x9 fixed-size
// eigenproblem of the 3D quadratic basis) once it is inlined here.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace uhpc::rk {

namespace {

// Monomials of the shifted, scaled basis at y = (x - x_I)/h: 1, y_i, then y_i y_j (i <= j).
template <int Dim, Basis B>
inline void fill_basis(const double* y, double* H) {
  H[0] = 1.0;
  if constexpr (B == Basis::Constant) return;
  for (int i = 0; i < Dim; ++i) H[1 + i] = y[i];
  if constexpr (B == Basis::Quadratic) {
    int m = 1 + Dim;
    for (int i = 0; i < Dim; ++i)
      for (int j = i; j < Dim; ++j) H[m++] = y[i] * y[j];
  }
}

// Quasi-linear regularisation: lift the eigenvalues of S below relative_floor * lambda_max(S) up to
// that floor. Only the deficient directions change (across a line of nodes, out of a plane), so
// reproduction along the well-supported ones stays exact.
template <int NL>
void lift_small_eigenvalues(double relative_floor, Eigen::Matrix<double, NL, NL>& S) {
  using Block = Eigen::Matrix<double, NL, NL>;
  const Eigen::SelfAdjointEigenSolver<Block> eig(S);
  const auto& lambda = eig.eigenvalues();  // ascending
  const double floor = relative_floor * std::max(lambda(NL - 1), 0.0);
  for (int k = 0; k < NL && lambda(k) < floor; ++k) {
    const auto v = eig.eigenvectors().col(k);
    S += (floor - lambda(k)) * v * v.transpose();
  }
}

// Shape functions with basis B = [1, H_L] from the kernel values already stored in psi[k], by block
// elimination of the constant monomial. With m00 = sum w_I, the weighted mean Hbar = sum w_I H_L,I / m00
// and the weighted covariance S = sum w_I (H_L,I - Hbar)(H_L,I - Hbar)^T, the system M b = r becomes
//   Psi_I   = w_I (1/m00 + (H_L,I - Hbar)^T c_0),   S c_0 = -Hbar,
//   Psi^i_I = w_I (H_L,I - Hbar)^T c_i,             S c_i = -(1/h) e_i.
// It is the same solution as with the full M, but partition of unity (and the zero sum of the
// gradients) no longer depend on the solve at all: sum_I w_I (H_L,I - Hbar) = 0 up to round-off. The
// conditioning check and the quasi-linear regularisation both act on S, the part that carries the
// geometry of the neighbourhood. Returns false (psi untouched) when S is ill conditioned and
// `regularize` is off.
template <int Dim, Basis B>
bool solve_basis(const Options& options, bool regularize, const double* x, const double* nodes,
                 const std::int32_t* nbr, int n, double h, double m00, double* psi, double* grad,
                 PointResult& result) {
  constexpr int NB = basis_size(Dim, B);
  constexpr int NL = NB - 1;
  using Mat = Eigen::Matrix<double, NL, NL>;
  using Vec = Eigen::Matrix<double, NL, 1>;
  using Rhs = Eigen::Matrix<double, NL, 1 + Dim>;

  const double inv_h = 1.0 / h;
  double H[NB], y[Dim];
  auto basis_at = [&](int k) {
    const double* xi = nodes + static_cast<std::size_t>(nbr[k]) * Dim;
    for (int d = 0; d < Dim; ++d) y[d] = (x[d] - xi[d]) * inv_h;
    fill_basis<Dim, B>(y, H);
    return Eigen::Map<const Vec>(H + 1);
  };

  Vec first = Vec::Zero();
  Mat second = Mat::Zero();
  for (int k = 0; k < n; ++k) {
    const double w = psi[k];
    if (w == 0.0) continue;
    const auto HL = basis_at(k);
    first.noalias() += w * HL;
    second.noalias() += w * HL * HL.transpose();
  }
  const Vec mean = first / m00;
  Mat S = second - m00 * mean * mean.transpose();
  if (regularize) lift_small_eigenvalues<NL>(options.ql_regularization, S);

  const Eigen::LLT<Mat> llt(S);
  const double rcond = llt.info() == Eigen::Success ? llt.rcond() : 0.0;
  if (!(rcond >= options.rcond_min) && !(regularize && rcond > 0.0)) return false;
  result.rcond = rcond;
  result.basis = B;

  Rhs rhs = Rhs::Zero();
  rhs.col(0) = -mean;
  for (int i = 0; i < Dim; ++i) rhs(i, 1 + i) = -inv_h;  // rows 0..Dim-1 of H_L are the linear monomials
  Rhs coef = llt.solve(rhs);
  if (regularize) coef += llt.solve(rhs - S * coef);  // one refinement step on the worse-conditioned path

  auto terms = [&](int k) -> Eigen::Matrix<double, 1, 1 + Dim> {
    return psi[k] * ((basis_at(k) - mean).transpose() * coef);
  };
  // On the regularised path the coefficients are large in the deficient directions, and the round-off
  // of sum_I w_I (H_L,I - Hbar) (about eps) is amplified into the partition of unity (about 1e-13).
  // Removing that defect along the Shepard weights w_I/m00 restores sum Psi = 1 and sum grad Psi = 0
  // to round-off while changing each Psi_I by no more than the defect itself.
  Eigen::Matrix<double, 1, 1 + Dim> defect = Eigen::Matrix<double, 1, 1 + Dim>::Zero();
  if (regularize) {
    double shepard_sum = 0.0;
    for (int k = 0; k < n; ++k)
      if (psi[k] != 0.0) {
        defect += terms(k);
        shepard_sum += psi[k] / m00;
      }
    defect(0) += shepard_sum - 1.0;
  }
  for (int k = 0; k < n; ++k) {
    const double w = psi[k];
    if (w == 0.0) {
      if (options.gradients)
        for (int d = 0; d < Dim; ++d) grad[k * Dim + d] = 0.0;
      continue;
    }
    const Eigen::Matrix<double, 1, 1 + Dim> v = terms(k) - (w / m00) * defect;
    psi[k] = w / m00 + v(0);
    if (options.gradients)
      for (int d = 0; d < Dim; ++d) grad[k * Dim + d] = v(1 + d);
  }
  return true;
}

// Shepard functions (constant basis). A constant basis has no linear monomial to carry implicit
// gradients, so gradients are the direct derivatives of w_I / sum_J w_J, which still sum to zero.
template <int Dim>
void shepard(const Options& options, const double* x, const double* nodes, const double* support_radius,
             const std::int32_t* nbr, int n, double m00, double* psi, double* grad, PointResult& result) {
  result.basis = Basis::Constant;
  result.rcond = 1.0;
  double sum_dw[Dim] = {};
  if (options.gradients) {
    for (int k = 0; k < n; ++k) {
      const double* xi = nodes + static_cast<std::size_t>(nbr[k]) * Dim;
      const double a = support_radius[nbr[k]];
      double r2 = 0.0;
      for (int d = 0; d < Dim; ++d) r2 += (x[d] - xi[d]) * (x[d] - xi[d]);
      const double r = std::sqrt(r2);
      const KernelValue kv = kernel_value(options.kernel, r / a);
      for (int d = 0; d < Dim; ++d) {
        // dw/dx = w'(z) (x - x_I) / (r a); w'(0) = 0 so the limit at r = 0 is 0.
        grad[k * Dim + d] = r > 0.0 ? kv.dw_dz * (x[d] - xi[d]) / (r * a) : 0.0;
        sum_dw[d] += grad[k * Dim + d];
      }
    }
    for (int k = 0; k < n; ++k)
      for (int d = 0; d < Dim; ++d) grad[k * Dim + d] = (grad[k * Dim + d] - psi[k] * sum_dw[d] / m00) / m00;
  }
  for (int k = 0; k < n; ++k) psi[k] /= m00;
}

// Derivatives of the monomials with respect to y_d (the basis of fill_basis).
template <int Dim, Basis B>
inline void fill_basis_derivative(const double* y, int d, double* dH) {
  constexpr int NB = basis_size(Dim, B);
  for (int m = 0; m < NB; ++m) dH[m] = 0.0;
  if constexpr (B == Basis::Constant) return;
  dH[1 + d] = 1.0;
  if constexpr (B == Basis::Quadratic) {
    int m = 1 + Dim;
    for (int i = 0; i < Dim; ++i)
      for (int j = i; j < Dim; ++j, ++m) dH[m] = (i == d ? y[j] : 0.0) + (j == d ? y[i] : 0.0);
  }
}

// Direct derivatives (Derivatives::Direct) of Psi_I = H_I^T b w_I, M b = H(0), H_I = H((x - x_I)/h):
//   d_d Psi_I = (d_d b)^T H_I w_I + b^T (d_d H_I) w_I + b^T H_I d_d w_I,   M d_d b = -(d_d M) b,
//   d_d M = sum_J d_d w_J H_J H_J^T + w_J (d_d H_J H_J^T + H_J d_d H_J^T).
// Overwrites grad (nothing is written when M cannot be factorized: false); psi from solve_basis is
// left as it is.
template <int Dim, Basis B>
bool direct_gradients(const Options& options, const double* x, const double* nodes, const double* support_radius,
                      const std::int32_t* nbr, int n, double h, double* grad) {
  constexpr int NB = basis_size(Dim, B);
  using Mat = Eigen::Matrix<double, NB, NB>;
  using Vec = Eigen::Matrix<double, NB, 1>;
  const double inv_h = 1.0 / h;
  // One neighbour's basis, its y-derivatives (scaled to x-derivatives by 1/h) and kernel gradient.
  struct Local {
    Vec H;
    Vec dH[Dim];
    double w = 0.0, dw[Dim] = {};
  };
  auto local_at = [&](int k) {
    Local l;
    const double* xi = nodes + static_cast<std::size_t>(nbr[k]) * Dim;
    const double a = support_radius[nbr[k]];
    double y[Dim], r2 = 0.0;
    for (int d = 0; d < Dim; ++d) {
      y[d] = (x[d] - xi[d]) * inv_h;
      r2 += (x[d] - xi[d]) * (x[d] - xi[d]);
    }
    fill_basis<Dim, B>(y, l.H.data());
    for (int d = 0; d < Dim; ++d) {
      fill_basis_derivative<Dim, B>(y, d, l.dH[d].data());
      l.dH[d] *= inv_h;
    }
    const double r = std::sqrt(r2);
    const KernelValue kv = kernel_value(options.kernel, r / a);
    l.w = kv.w;
    for (int d = 0; d < Dim; ++d) l.dw[d] = r > 0.0 ? kv.dw_dz * (x[d] - xi[d]) / (r * a) : 0.0;  // w'(0) = 0
    return l;
  };
  Mat M = Mat::Zero();
  Mat dM[Dim];
  for (int d = 0; d < Dim; ++d) dM[d].setZero();
  for (int k = 0; k < n; ++k) {
    const Local l = local_at(k);
    if (l.w == 0.0) continue;  // outside the support (w and its derivative vanish at the edge)
    M.noalias() += l.w * l.H * l.H.transpose();
    for (int d = 0; d < Dim; ++d) {
      const Mat outer = l.dH[d] * l.H.transpose();
      dM[d].noalias() += l.dw[d] * l.H * l.H.transpose() + l.w * (outer + outer.transpose());
    }
  }
  const Eigen::LDLT<Mat> ldlt(M);
  if (ldlt.info() != Eigen::Success) return false;
  const Vec b = ldlt.solve(Vec::Unit(0));
  Vec db[Dim];
  bool finite = b.allFinite();
  for (int d = 0; d < Dim; ++d) {
    db[d] = ldlt.solve(-(dM[d] * b));
    finite = finite && db[d].allFinite();
  }
  if (!finite) return false;
  for (int k = 0; k < n; ++k) {
    const Local l = local_at(k);
    for (int d = 0; d < Dim; ++d)
      grad[k * Dim + d] = (db[d].dot(l.H) + b.dot(l.dH[d])) * l.w + b.dot(l.H) * l.dw[d];
  }
  return true;
}

template <int Dim>
bool direct(const Options& options, Basis basis, const double* x, const double* nodes, const double* support_radius,
            const std::int32_t* nbr, int n, double h, double* grad) {
  switch (basis) {
    case Basis::Linear:
      return direct_gradients<Dim, Basis::Linear>(options, x, nodes, support_radius, nbr, n, h, grad);
    case Basis::Quadratic:
      return direct_gradients<Dim, Basis::Quadratic>(options, x, nodes, support_radius, nbr, n, h, grad);
    case Basis::Constant:
      break;
  }
  return false;
}

template <int Dim>
bool solve(const Options& options, Basis basis, bool regularize, const double* x, const double* nodes,
           const std::int32_t* nbr, int n, double h, double m00, double* psi, double* grad, PointResult& result) {
  switch (basis) {
    case Basis::Linear:
      return solve_basis<Dim, Basis::Linear>(options, regularize, x, nodes, nbr, n, h, m00, psi, grad, result);
    case Basis::Quadratic:
      return solve_basis<Dim, Basis::Quadratic>(options, regularize, x, nodes, nbr, n, h, m00, psi, grad, result);
    case Basis::Constant:
      break;
  }
  return false;
}

}  // namespace

template <int Dim>
PointResult evaluate(const Options& options, const double* x, const double* nodes, const double* support_radius,
                     const std::int32_t* nbr, int n, double* psi, double* grad) {
  PointResult result;
  // Kernel values first (kept in psi), and the scale h of the basis.
  double h = 0.0, m00 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double* xi = nodes + static_cast<std::size_t>(nbr[k]) * Dim;
    const double a = support_radius[nbr[k]];
    double r2 = 0.0;
    for (int d = 0; d < Dim; ++d) r2 += (x[d] - xi[d]) * (x[d] - xi[d]);
    psi[k] = kernel_value(options.kernel, std::sqrt(r2) / a).w;
    m00 += psi[k];
    h = std::max(h, a);
  }
  if (!(m00 > 0.0)) {
    std::fill(psi, psi + n, 0.0);
    if (options.gradients) std::fill(grad, grad + static_cast<std::ptrdiff_t>(n) * Dim, 0.0);
    return result;  // Path::Empty
  }

  Basis basis = options.basis;
  while (basis != Basis::Constant) {
    if (solve<Dim>(options, basis, false, x, nodes, nbr, n, h, m00, psi, grad, result)) {
      result.path = basis == options.basis ? Path::Full : Path::Fallback;
      // grad keeps the implicit gradients if M fails to factorize (not expected where S passed its
      // condition test).
      if (options.gradients && options.derivatives == Derivatives::Direct)
        direct<Dim>(options, basis, x, nodes, support_radius, nbr, n, h, grad);
      return result;
    }
    if (options.ill_conditioning == IllConditioning::QuasiLinear &&
        solve<Dim>(options, basis, true, x, nodes, nbr, n, h, m00, psi, grad, result)) {
      result.path = basis == options.basis ? Path::QuasiLinear : Path::Fallback;
      return result;
    }
    basis = basis == Basis::Quadratic ? Basis::Linear : Basis::Constant;
  }
  shepard<Dim>(options, x, nodes, support_radius, nbr, n, m00, psi, grad, result);
  result.path = options.basis == Basis::Constant ? Path::Full : Path::Fallback;
  return result;
}

std::size_t ShapeTable::count(Path path) const {
  return static_cast<std::size_t>(
      std::count_if(info.begin(), info.end(), [path](const PointResult& r) { return r.path == path; }));
}

template <int Dim>
ShapeTable build_shape_table(const Options& options, const double* queries, std::size_t n_queries,
                             const double* nodes, const double* support_radius, std::size_t n_nodes) {
  ShapeTable table;
  table.dim = Dim;
  table.support = nodes_covering<Dim>(queries, n_queries, nodes, support_radius, n_nodes);
  const std::size_t entries = table.support.indices.size();
  table.psi.resize(entries);
  if (options.gradients) table.grad.resize(entries * Dim);
  table.info.resize(n_queries);
  const std::int64_t nq = static_cast<std::int64_t>(n_queries);
#pragma omp parallel for schedule(dynamic, 128)
  for (std::int64_t p = 0; p < nq; ++p) {
    const std::int64_t b = table.support.begin(p);
    table.info[p] = evaluate<Dim>(options, queries + p * Dim, nodes, support_radius, table.support.row(p),
                                  static_cast<int>(table.support.count(p)), table.psi.data() + b,
                                  options.gradients ? table.grad.data() + b * Dim : nullptr);
  }
  return table;
}

std::string path_name(Path path) {
  switch (path) {
    case Path::Full: return "full";
    case Path::QuasiLinear: return "quasi_linear";
    case Path::Fallback: return "fallback";
    case Path::Empty: return "empty";
  }
  return "unknown";
}

std::string basis_name(Basis basis) {
  switch (basis) {
    case Basis::Constant: return "constant";
    case Basis::Linear: return "linear";
    case Basis::Quadratic: return "quadratic";
  }
  return "unknown";
}

Derivatives derivatives_from_name(const std::string& name) {
  if (name == "implicit") return Derivatives::Implicit;
  if (name == "direct") return Derivatives::Direct;
  throw std::invalid_argument("unknown derivatives '" + name + "', expected one of: implicit, direct");
}

std::string derivatives_name(Derivatives d) { return d == Derivatives::Direct ? "direct" : "implicit"; }

Basis basis_from_name(const std::string& name) {
  if (name == "constant") return Basis::Constant;
  if (name == "linear") return Basis::Linear;
  if (name == "quadratic") return Basis::Quadratic;
  throw std::invalid_argument("unknown basis '" + name + "', expected one of: constant, linear, quadratic");
}

template PointResult evaluate<2>(const Options&, const double*, const double*, const double*, const std::int32_t*,
                                 int, double*, double*);
template PointResult evaluate<3>(const Options&, const double*, const double*, const double*, const std::int32_t*,
                                 int, double*, double*);
template ShapeTable build_shape_table<2>(const Options&, const double*, std::size_t, const double*, const double*,
                                         std::size_t);
template ShapeTable build_shape_table<3>(const Options&, const double*, std::size_t, const double*, const double*,
                                         std::size_t);

}  // namespace uhpc::rk
