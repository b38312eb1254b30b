#include "bordered_tangent_solver.hpp"

#include <algorithm>
#include <utility>

#include <Eigen/Dense>
#include <Eigen/UmfPackSupport>

#include "preconditioned_gmres.hpp"

namespace uhpc::micro {

struct BorderedTangentSolver::Lu : Eigen::UmfPackLU<Eigen::SparseMatrix<double>> {};

BorderedTangentSolver::BorderedTangentSolver(const TangentSolverOptions& options) : o_(options) {}
BorderedTangentSolver::~BorderedTangentSolver() = default;

BorderedTangentSolver::Parts BorderedTangentSolver::parts_of(const BorderedTangent& tangent, double row_scale) {
  return {tangent.point_blocks(), row_scale * tangent.constraint_row(), row_scale};
}

Eigen::VectorXd BorderedTangentSolver::rhs(const Eigen::VectorXd& r, double cres, double scale) const {
  const auto N = r.size();
  Eigen::VectorXd b(N + 1);
  b.head(N) = -r;
  b[N] = -cres * scale;
  return b;
}

BorderedTangentSolver::Correction BorderedTangentSolver::solve(long key, bool start_of_step, double row_scale,
                                                               const BorderedTangent& tangent, const Eigen::VectorXd& r,
                                                               double cres, double tolerance) {
  Correction c;
  const bool same_pattern = lu_ && key == lu_key_;
  bool solved = false;
  if (o_.update == TangentUpdate::Gmres) {
    if (!solve_gmres(key, same_pattern, start_of_step, tangent, row_scale, r, cres, tolerance, c.x)) {
      c.why = "UMFPACK: singular bordered tangent";
      return c;
    }
    solved = true;
  } else if (same_pattern && tangent.point_columns().cols() == Q_.cols()) {
    Parts p = start_of_step ? last_ : parts_of(tangent, row_scale);
    if (solve_low_rank(p, rhs(r, cres, p.scale), tolerance, c.x)) {
      last_ = std::move(p);
      solved = true;
    }
  }
  if (!solved) {  // LowRank: factorize the new tangent
    J_ = tangent.matrix(row_scale);
    if (!factorize(key)) {
      c.why = "UMFPACK: singular bordered tangent";
      return c;
    }
    factorized_ = parts_of(tangent, row_scale);
    last_ = factorized_;
    Q_ = tangent.point_columns();
    Q_.conservativeResize(J_.rows(), Q_.cols());
    kept_key_.clear();
    kept_.clear();
    c.x = lu_->solve(rhs(r, cres, row_scale));
  }
  if (!c.x.allFinite()) {
    c.why = "UMFPACK: non-finite correction";
    return c;
  }
  c.ok = true;
  return c;
}

bool BorderedTangentSolver::factorize(long key) {
  if (!lu_ || key != lu_key_) {
    lu_ = std::make_unique<Lu>();
    // No iterative refinement: Newton's own iterations correct the residual; refinement would only
    // repeat a solve and a residual product per iteration (12 % of a run, same result).
    lu_->umfpackControl()(UMFPACK_IRSTEP) = 0;
    lu_->analyzePattern(J_);
    lu_key_ = key;
  }
  lu_->factorize(J_);  // keeps a reference to J_ (a member: it must outlive every solve)
  ++factorizations_;
  if (lu_->info() != Eigen::Success) {
    lu_.reset();
    return false;
  }
  return true;
}

bool BorderedTangentSolver::accurate(const Eigen::VectorXd& residual, const Eigen::VectorXd& b, double tolerance) const {
  return residual.allFinite() && residual.norm() <= std::max(0.01 * tolerance, 1e-13 * b.norm());
}

std::size_t BorderedTangentSolver::column_of(long slot_key, const Eigen::VectorXd& u) {
  const auto at = std::find(kept_key_.begin(), kept_key_.end(), slot_key);
  if (at != kept_key_.end()) return static_cast<std::size_t>(at - kept_key_.begin());
  kept_key_.push_back(slot_key);
  kept_.push_back(lu_->solve(u));
  ++update_columns_;
  return kept_.size() - 1;
}

// A = A0 + U C V^T with A0 = J_ (factorized), U = V = the jump columns Q_p of the changed points and
// C = blockdiag(C_p - C0_p); a changed constraint row adds U = e_N, V = its change, C = 1. Then
//   x = x0 - Z (I + C V^T Z)^-1 C V^T x0,   x0 = A0^-1 b,   Z = A0^-1 U (kept per column).
bool BorderedTangentSolver::solve_low_rank(const Parts& p, const Eigen::VectorXd& b, double tolerance,
                                           Eigen::VectorXd& x) {
  const Eigen::Index n = J_.rows();
  std::vector<Eigen::Index> changed;
  for (std::size_t i = 0; i < p.blocks.size(); ++i)
    if (p.blocks[i] != factorized_.blocks[i]) changed.push_back(static_cast<Eigen::Index>(i));
  const Eigen::VectorXd row_change = p.row - factorized_.row;
  const bool border = (row_change.array() != 0.0).any();
  const auto k = static_cast<Eigen::Index>(2 * changed.size()) + (border ? 1 : 0);
  if (k == 0) {
    x = lu_->solve(b);
    return true;
  }
  if (k > o_.max_update_rank) return false;
  std::size_t missing = border && std::find(kept_key_.begin(), kept_key_.end(), -1L) == kept_key_.end() ? 1 : 0;
  for (Eigen::Index i : changed)
    missing += 2 * static_cast<std::size_t>(std::find(kept_key_.begin(), kept_key_.end(), 2 * i) == kept_key_.end());
  if (kept_.size() + missing > static_cast<std::size_t>(o_.max_update_rank)) return false;

  std::vector<std::size_t> Z(static_cast<std::size_t>(k));  // the kept columns A0^-1 U
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(k, k);
  for (std::size_t j = 0; j < changed.size(); ++j) {
    const Eigen::Index i = changed[j];
    for (int a = 0; a < 2; ++a) {
      Z[2 * j + a] = column_of(2 * i + a, Eigen::VectorXd(Q_.col(2 * i + a)));
      for (int c = 0; c < 2; ++c)
        C(static_cast<Eigen::Index>(2 * j) + a, static_cast<Eigen::Index>(2 * j) + c) =
            p.blocks[i][2 * a + c] - factorized_.blocks[i][2 * a + c];
    }
  }
  if (border) {
    Z[static_cast<std::size_t>(k - 1)] = column_of(-1, Eigen::VectorXd::Unit(n, n - 1));
    C(k - 1, k - 1) = 1.0;
  }
  // V^T v for a vector v of length N + 1.
  const auto project = [&](const Eigen::VectorXd& v) {
    Eigen::VectorXd w(k);
    for (std::size_t j = 0; j < changed.size(); ++j)
      for (int a = 0; a < 2; ++a) w[static_cast<Eigen::Index>(2 * j) + a] = Q_.col(2 * changed[j] + a).dot(v);
    if (border) w[k - 1] = row_change.dot(v);
    return w;
  };
  Eigen::MatrixXd S = Eigen::MatrixXd::Identity(k, k);
  Eigen::MatrixXd VtZ(k, k);
  for (Eigen::Index j = 0; j < k; ++j) VtZ.col(j) = project(kept_[Z[static_cast<std::size_t>(j)]]);
  S.noalias() += C * VtZ;
  const Eigen::PartialPivLU<Eigen::MatrixXd> capacitance(S);
  const auto apply = [&](const Eigen::VectorXd& rhs) {
    Eigen::VectorXd y = lu_->solve(rhs);
    const Eigen::VectorXd s = capacitance.solve(C * project(y));
    for (Eigen::Index j = 0; j < k; ++j) y -= s[j] * kept_[Z[static_cast<std::size_t>(j)]];
    return y;
  };
  // b - A x, with A x = A0 x + U C V^T x.
  const auto residual = [&](const Eigen::VectorXd& v) {
    Eigen::VectorXd e = b - J_ * v;
    const Eigen::VectorXd w = C * project(v);
    for (std::size_t j = 0; j < changed.size(); ++j)
      for (int a = 0; a < 2; ++a) e -= w[static_cast<Eigen::Index>(2 * j) + a] * Q_.col(2 * changed[j] + a);
    if (border) e[n - 1] -= w[k - 1];
    return e;
  };
  x = apply(b);
  Eigen::VectorXd e = residual(x);
  if (!accurate(e, b, tolerance)) {  // one refinement (the capacitance of a nearly singular tangent)
    x += apply(e);
    e = residual(x);
  }
  if (!accurate(e, b, tolerance)) return false;
  ++update_corrections_;
  return true;
}

bool BorderedTangentSolver::solve_gmres(long key, bool same_pattern, bool start_of_step, const BorderedTangent& tangent,
                                        double row_scale, const Eigen::VectorXd& r, double cres, double tolerance,
                                        Eigen::VectorXd& x) {
  const bool reuse = start_of_step && same_pattern;
  const bool krylov = same_pattern && o_.krylov_iterations > 0 && (!reuse || last_by_krylov_);
  if (!reuse) {
    new_row_scale_ = row_scale;
    J_new_ = tangent.matrix(new_row_scale_);
  }
  const bool on_new = !reuse || last_by_krylov_;  // the tangent is J_new_, else J_ (factorized)
  const Eigen::VectorXd b = rhs(r, cres, on_new ? new_row_scale_ : lu_row_scale_);
  bool solved = false;
  if (krylov) {
    const GmresResult k = preconditioned_gmres(
        J_new_, [this](const Eigen::VectorXd& v, Eigen::VectorXd& z) { z = lu_->solve(v); }, b,
        std::max(0.01 * tolerance, 1e-13 * b.norm()), o_.krylov_iterations, x);
    krylov_products_ += static_cast<std::size_t>(k.iterations);
    solved = k.converged && x.allFinite();
    if (solved) ++krylov_corrections_;
  }
  if (!solved && on_new) {
    std::swap(J_, J_new_);
    lu_row_scale_ = new_row_scale_;
    if (!factorize(key)) return false;
  }
  if (!solved) x = lu_->solve(b);
  last_by_krylov_ = solved;
  return true;
}

}  // namespace uhpc::micro
