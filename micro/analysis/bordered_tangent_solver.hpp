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
//  - otherwise the new tangent is solved with the factorization at hand, because between Newton
//    iterations on one crack geometry the tangent changes at the cohesive points only (the bulk is
//    linear): K_T = K_lin + sum_p Q_p C_p Q_p^T (FractureSystem::point_tangents), so the new matrix is
//    the factorized one plus a low-rank term, and
//      TangentUpdate::LowRank: the Sherman-Morrison-Woodbury formula on the points whose C_p
//        changed since the factorization (and the constraint row, if it changed): A0^-1 of their jump
//        columns is solved once per point and kept until the next factorization, so a correction costs
//        one triangular solve plus a dense system of twice the changed points; the new tangent is
//        factorized only when more than `max_update_rank` columns would be needed;
//      TangentUpdate::Gmres (default): GMRES preconditioned with the factorization (preconditioned_gmres.hpp),
//        about rank + 1 triangular solves per correction; the new tangent is factorized when GMRES does
//        not converge in `krylov_iterations`.
//    Either way a correction is accepted only with its true residual |b - A x| within a hundredth of
//    Newton's tolerance; otherwise the new tangent is factorized.
// A pure numerical component: no knowledge of cracks or cells.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Sparse>

namespace uhpc::micro {

// [choice] How a Newton correction is solved on a tangent that is not the factorized one (above).
enum class TangentUpdate { LowRank, Gmres };

// The bordered tangent of the current iterate, in the parts the solver uses:
//   A(s) = [[K_fixed + sum_p Q_p C_p Q_p^T, -f], [s row^T]]   (row: N + 1 entries, the corner last).
class BorderedTangent {
 public:
  virtual ~BorderedTangent() = default;
  // The assembled matrix with the constraint row scaled by `row_scale` (what a factorization takes).
  virtual Eigen::SparseMatrix<double> matrix(double row_scale) const = 0;
  // The unscaled constraint row.
  virtual Eigen::VectorXd constraint_row() const = 0;
  // Q: N x 2m, the columns 2p, 2p + 1 of point p (the same for every tangent of one pattern key).
  virtual const Eigen::SparseMatrix<double>& point_columns() const = 0;
  // C_p, row-major, per point.
  virtual const std::vector<std::array<double, 4>>& point_blocks() const = 0;
};

struct TangentSolverOptions {
  TangentUpdate update = TangentUpdate::Gmres;
  int max_update_rank = 64;    // LowRank: kept columns (two per changed point) before a factorization
  int krylov_iterations = 16;  // Gmres: iterations before a factorization (0: factorize every new tangent)
};

class BorderedTangentSolver {
 public:
  struct Correction {
    bool ok = false;
    Eigen::VectorXd x;  // (dd, dlambda)
    std::string why;    // when !ok
  };

  explicit BorderedTangentSolver(const TangentSolverOptions& options);
  ~BorderedTangentSolver();
  BorderedTangentSolver(const BorderedTangentSolver&) = delete;
  BorderedTangentSolver& operator=(const BorderedTangentSolver&) = delete;

  // The Newton correction for the residual `r` and constraint residual `cres` (unscaled). `key` names
  // the sparsity pattern (same key, same pattern and point columns); `row_scale` is the constraint row's
  // scale for a new tangent (a reused one keeps the scale it was made with); `tolerance` is Newton's
  // on |r|.
  Correction solve(long key, bool start_of_step, double row_scale, const BorderedTangent& tangent,
                   const Eigen::VectorXd& r, double cres, double tolerance);

  std::size_t factorizations() const { return factorizations_; }
  std::size_t krylov_corrections() const { return krylov_corrections_; }
  std::size_t krylov_products() const { return krylov_products_; }
  std::size_t update_corrections() const { return update_corrections_; }  // LowRank corrections
  std::size_t update_columns() const { return update_columns_; }          // their kept columns' solves

 private:
  struct Lu;  // UMFPACK's LU (in the .cpp: its header stays out of every user's)
  // A tangent in the solver's terms: its point blocks, its scaled constraint row and that scale.
  struct Parts {
    std::vector<std::array<double, 4>> blocks;
    Eigen::VectorXd row;
    double scale = 1.0;
  };
  static Parts parts_of(const BorderedTangent& tangent, double row_scale);
  Eigen::VectorXd rhs(const Eigen::VectorXd& r, double cres, double scale) const;
  bool factorize(long key);  // J_
  bool accurate(const Eigen::VectorXd& residual, const Eigen::VectorXd& b, double tolerance) const;
  bool solve_low_rank(const Parts& p, const Eigen::VectorXd& b, double tolerance, Eigen::VectorXd& x);
  bool solve_gmres(long key, bool same_pattern, bool start_of_step, const BorderedTangent& tangent, double row_scale,
                   const Eigen::VectorXd& r, double cres, double tolerance, Eigen::VectorXd& x);
  // The index in kept_ of A0^-1 u for the column named `slot_key` (solved on first use).
  std::size_t column_of(long slot_key, const Eigen::VectorXd& u);

  TangentSolverOptions o_;
  std::unique_ptr<Lu> lu_;
  long lu_key_ = -1;
  Eigen::SparseMatrix<double> J_;  // the tangent lu_ factorized (UMFPACK keeps a reference to it)
  Eigen::SparseMatrix<double> Q_;  // its point columns, padded to N + 1 rows
  Parts factorized_, last_;        // LowRank: the parts of J_ and of the last corrected tangent
  // LowRank: A0^-1 of the columns a correction needed so far (point p: keys 2p, 2p + 1; the border: -1).
  std::vector<long> kept_key_;
  std::vector<Eigen::VectorXd> kept_;
  // Gmres: the current tangent, when GMRES solves it with lu_, and its row scale.
  Eigen::SparseMatrix<double> J_new_;
  double lu_row_scale_ = 1.0, new_row_scale_ = 1.0;
  bool last_by_krylov_ = false;  // the last correction solved J_new_ by GMRES (J_ is older)
  std::size_t factorizations_ = 0, krylov_corrections_ = 0, krylov_products_ = 0;
  std::size_t update_corrections_ = 0, update_columns_ = 0;
};

}  // namespace uhpc::micro
