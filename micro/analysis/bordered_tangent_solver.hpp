#pragma once
// The linear solver of the crack analysis's Newton iterations: the bordered tangent
//   [ K_T(d)   -f_unit ] [dd     ]   [ -r      ]
//   [ s g^T     s c    ] [dlambda] = [ -s cres ]
// (one constraint row: g = 0, c = 1 holds the far-face displacement, c = 0 an opening integral g.d;
// scaled by s so that its tolerance is the residual's; FractureSystem::bordered) is solved by a sparse LU
// (UMFPACK; the tangent is not symmetric), and factorizations are spent only where they pay:
//  - the ordering and symbolic analysis are kept per pattern key (one per crack stage and constraint);
//  - the first iteration of a path step may reuse the last tangent (`start_of_step`), which still has
//    the points that were softening on their softening branch: the better predictor;
//  - otherwise GMRES preconditioned with the factorization at hand solves the new tangent (it differs
//    at the cohesive points only, a low-rank change: preconditioned_gmres.hpp), and only when GMRES
//    does not converge in `krylov_iterations` is the new tangent factorized.
// A pure numerical component: no knowledge of cracks or cells.
#include <functional>
#include <memory>
#include <string>

#include <Eigen/Sparse>

namespace uhpc::micro {

class BorderedTangentSolver {
 public:
  // The bordered tangent at the current iterate with its constraint row scaled by `row_scale`.
  using Assemble = std::function<Eigen::SparseMatrix<double>(double row_scale)>;

  struct Correction {
    bool ok = false;
    Eigen::VectorXd x;  // (dd, dlambda)
    std::string why;    // when !ok
  };

  // GMRES iterations allowed before the new tangent is factorized (0: factorize every iteration).
  explicit BorderedTangentSolver(int krylov_iterations);
  ~BorderedTangentSolver();
  BorderedTangentSolver(const BorderedTangentSolver&) = delete;
  BorderedTangentSolver& operator=(const BorderedTangentSolver&) = delete;

  // The Newton correction for the residual `r` and constraint residual `cres` (unscaled). `key` names
  // the sparsity pattern (same key, same pattern); `row_scale` is the constraint row's scale for a
  // newly assembled tangent (a reused one keeps the scale it was made with); `tolerance` is Newton's
  // on |r| (GMRES is converged to a hundredth of it).
  Correction solve(long key, bool start_of_step, double row_scale, const Assemble& assemble, const Eigen::VectorXd& r,
                   double cres, double tolerance);

  std::size_t factorizations() const { return factorizations_; }
  std::size_t krylov_corrections() const { return krylov_corrections_; }
  std::size_t krylov_products() const { return krylov_products_; }

 private:
  struct Lu;  // UMFPACK's LU (in the .cpp: its header stays out of every user's)
  bool factorize(long key);

  int krylov_iterations_;
  std::unique_ptr<Lu> lu_;
  long lu_key_ = -1;
  Eigen::SparseMatrix<double> J_;      // the tangent lu_ factorized (UMFPACK keeps a reference to it)
  Eigen::SparseMatrix<double> J_new_;  // the current one, when GMRES solves it with lu_
  double lu_row_scale_ = 1.0, new_row_scale_ = 1.0;  // the constraint row's scale in J_, J_new_
  bool last_by_krylov_ = false;  // the last correction solved J_new_ by GMRES (J_ is older)
  std::size_t factorizations_ = 0, krylov_corrections_ = 0, krylov_products_ = 0;
};

}  // namespace uhpc::micro
