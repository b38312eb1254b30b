#include "bordered_tangent_solver.hpp"

#include <algorithm>
#include <utility>

#include <Eigen/UmfPackSupport>

#include "preconditioned_gmres.hpp"

namespace uhpc::micro {

struct BorderedTangentSolver::Lu : Eigen::UmfPackLU<Eigen::SparseMatrix<double>> {};

BorderedTangentSolver::BorderedTangentSolver(int krylov_iterations) : krylov_iterations_(krylov_iterations) {}
BorderedTangentSolver::~BorderedTangentSolver() = default;

BorderedTangentSolver::Correction BorderedTangentSolver::solve(long key, bool start_of_step, double row_scale,
                                                               const Assemble& assemble, const Eigen::VectorXd& r,
                                                               double cres, double tolerance) {
  Correction c;
  const bool same_pattern = lu_ && key == lu_key_;
  const bool reuse = start_of_step && same_pattern;
  const bool krylov = same_pattern && krylov_iterations_ > 0 && (!reuse || last_by_krylov_);
  if (!reuse) {
    new_row_scale_ = row_scale;
    J_new_ = assemble(new_row_scale_);
  }
  const bool on_new = !reuse || last_by_krylov_;  // the tangent is J_new_, else J_ (factorized)
  const auto N = r.size();
  Eigen::VectorXd rhs(N + 1);
  rhs.head(N) = -r;
  rhs[N] = -cres * (on_new ? new_row_scale_ : lu_row_scale_);
  bool solved = false;
  if (krylov) {
    const GmresResult k = preconditioned_gmres(
        J_new_, [this](const Eigen::VectorXd& v, Eigen::VectorXd& z) { z = lu_->solve(v); }, rhs,
        std::max(0.01 * tolerance, 1e-13 * rhs.norm()), krylov_iterations_, c.x);
    krylov_products_ += static_cast<std::size_t>(k.iterations);
    solved = k.converged && c.x.allFinite();
    if (solved) ++krylov_corrections_;
  }
  if (!solved && on_new) {
    std::swap(J_, J_new_);
    lu_row_scale_ = new_row_scale_;
    if (!factorize(key)) {
      c.why = "UMFPACK: singular bordered tangent";
      return c;
    }
  }
  if (!solved) c.x = lu_->solve(rhs);
  last_by_krylov_ = solved;
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

}  // namespace uhpc::micro
